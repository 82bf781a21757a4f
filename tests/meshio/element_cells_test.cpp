#include "ffdkit/meshio/element_cells.h"

#include <gtest/gtest.h>

namespace ffdkit::meshio {
namespace {

// One cell of `shape` over `points` (corners 0..n-1).
ElementQuality checkOne(CellShape shape, const Eigen::MatrixX3d& points) {
  ElementCells cells;
  std::vector<std::int32_t> corners(std::size_t(cornerCount(shape)));
  for (std::size_t i = 0; i < corners.size(); ++i) corners[i] = std::int32_t(i);
  cells.add(shape, corners.data(), 7);
  return checkElementCells(points, cells);
}

Eigen::MatrixX3d unitCube() {
  Eigen::MatrixX3d p(8, 3);
  p << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  return p;
}

TEST(ElementCells, ReferenceCellsHaveTheirVolumesAndRightAngles) {
  const ElementQuality hex = checkOne(CellShape::Hexahedron, 2.0 * unitCube());
  EXPECT_TRUE(hex.ok());
  EXPECT_NEAR(hex.minVolume, 8.0, 1e-14);
  EXPECT_NEAR(hex.minScaledJacobian, 1.0, 1e-14);

  Eigen::MatrixX3d tet(4, 3);
  tet << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  const ElementQuality t = checkOne(CellShape::Tetrahedron, tet);
  EXPECT_TRUE(t.ok());
  EXPECT_NEAR(t.minVolume, 1.0 / 6.0, 1e-15);

  Eigen::MatrixX3d prism(6, 3);
  prism << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 2, 1, 0, 2, 0, 1, 2;
  const ElementQuality p = checkOne(CellShape::Prism, prism);
  EXPECT_TRUE(p.ok());
  EXPECT_NEAR(p.minVolume, 1.0, 1e-14);  // triangle 1/2 times height 2

  Eigen::MatrixX3d pyramid(5, 3);
  pyramid << -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0, 0, 0, 3;
  const ElementQuality y = checkOne(CellShape::Pyramid, pyramid);
  EXPECT_TRUE(y.ok());
  EXPECT_NEAR(y.minVolume, 4.0, 1e-14);  // base 4 times height 3 over 3
}

TEST(ElementCells, MirroredCellsAreInverted) {
  Eigen::MatrixX3d mirrored = unitCube();
  mirrored.col(2) *= -1.0;  // a reflection turns every corner's frame left-handed
  const ElementQuality hex = checkOne(CellShape::Hexahedron, mirrored);
  EXPECT_EQ(hex.badCells, 1);
  ASSERT_EQ(hex.firstBadCells.size(), 1u);
  EXPECT_EQ(hex.firstBadCells[0], 7);  // the id given, not the index
  EXPECT_NEAR(hex.minVolume, -1.0, 1e-14);
  EXPECT_NEAR(hex.minScaledJacobian, -1.0, 1e-14);
}

TEST(ElementCells, OneFoldedCornerIsFoundThoughTheVolumeStaysPositive) {
  Eigen::MatrixX3d cube = unitCube();
  cube.row(6) << 0.1, 0.1, 0.1;  // the top corner pushed inside, behind the opposite corners
  const ElementQuality hex = checkOne(CellShape::Hexahedron, cube);
  EXPECT_GT(hex.minVolume, 0.0);
  EXPECT_EQ(hex.badCells, 1);
  EXPECT_LT(hex.minScaledJacobian, 0.0);
}

TEST(ElementCells, FlatTetrahedronIsDegenerate) {
  Eigen::MatrixX3d tet(4, 3);
  tet << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.3, 0.3, 0;
  EXPECT_EQ(checkOne(CellShape::Tetrahedron, tet).badCells, 1);
}

TEST(ElementCells, PlanarCellsUseTheirSignedArea) {
  Eigen::MatrixX3d quad(4, 3);
  quad << 0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0;
  const ElementQuality q = checkOne(CellShape::Quadrilateral, quad);
  EXPECT_TRUE(q.ok());
  EXPECT_NEAR(q.minVolume, 2.0, 1e-15);
  Eigen::MatrixX3d clockwise = quad.colwise().reverse();
  EXPECT_EQ(checkOne(CellShape::Quadrilateral, clockwise).badCells, 1);
}

TEST(ElementCells, CornerOutsideThePointsIsRefused) {
  ElementCells cells;
  const std::int32_t corners[4] = {0, 1, 2, 9};
  cells.add(CellShape::Tetrahedron, corners, 0);
  EXPECT_THROW(checkElementCells(Eigen::MatrixX3d::Zero(4, 3), cells), std::out_of_range);
}

TEST(ElementCells, TextNamesTheBadCells) {
  Eigen::MatrixX3d mirrored = unitCube();
  mirrored.col(0) *= -1.0;
  const ElementQuality q = checkOne(CellShape::Hexahedron, mirrored);
  EXPECT_EQ(badElementsText(q), "1 cell inverted or of zero volume (first: 7)");
  EXPECT_NE(elementQualityText(q).find("worst scaled Jacobian -1"), std::string::npos);
}

}  // namespace
}  // namespace ffdkit::meshio
