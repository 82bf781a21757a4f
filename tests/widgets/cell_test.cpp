#include "ffdkit/widgets/cell.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "ffdkit/widgets/widget_error.h"

namespace ffdkit::widgets {
namespace {

Eigen::MatrixX3d unitGrid(const Eigen::Vector3i& c) {
  Eigen::MatrixX3d p(c.prod(), 3);
  for (int k = 0; k < c.z(); ++k)
    for (int j = 0; j < c.y(); ++j)
      for (int i = 0; i < c.x(); ++i)
        p.row(i + c.x() * (j + c.y() * k)) << double(i) / (c.x() - 1), double(j) / (c.y() - 1), double(k) / (c.z() - 1);
  return p;
}

Eigen::MatrixX3d rows(const Eigen::MatrixX3d& p, const std::vector<Eigen::Index>& idx) {
  Eigen::MatrixX3d out(static_cast<Eigen::Index>(idx.size()), 3);
  for (std::size_t r = 0; r < idx.size(); ++r) out.row(static_cast<Eigen::Index>(r)) = p.row(idx[r]);
  return out;
}

TEST(Cell, FaceIndicesFollowTheQuadLoop) {
  const Eigen::Vector3i c(3, 3, 3);
  // Normal z: grid directions x then y; p00, p10, p11, p01.
  EXPECT_EQ(cellPointIndices(c, CellSpec::face(1, 0, 2, 2)),
            (std::vector<Eigen::Index>{19, 20, 23, 22}));
  EXPECT_EQ(cellPointIndices(c, CellSpec::edge(0, 2, 0, 0)), (std::vector<Eigen::Index>{6, 7}));
  EXPECT_EQ(cellPointIndices(c, CellSpec::slab(2, 2)).size(), 9u);
  EXPECT_EQ(cellPointIndices(c, CellSpec::box(1, 1, 1)).size(), 8u);
}

TEST(Cell, RejectsCellsOutsideTheGrid) {
  const Eigen::Vector3i c(2, 3, 2);
  EXPECT_THROW(cellPointIndices(c, CellSpec::edge(1, 0, 0, 0)), WidgetError);
  EXPECT_THROW(cellPointIndices(c, CellSpec::face(0, 2, 0, 2)), WidgetError);
  EXPECT_THROW(cellPointIndices(c, CellSpec::slab(1, 3)), WidgetError);
  EXPECT_THROW(cellPointIndices(c, CellSpec::point(0, 0, -1)), WidgetError);
  EXPECT_THROW(cellPointIndices(c, CellSpec::edge(0, 0, 0, 3)), WidgetError);
  EXPECT_THROW(cellPointIndices(c, CellSpec::custom({})), WidgetError);
  EXPECT_THROW(cellPointIndices(c, CellSpec::custom({1, 1})), WidgetError);
  EXPECT_THROW(cellPointIndices(c, CellSpec::custom({12})), WidgetError);
  try {
    cellPointIndices(c, CellSpec::face(0, 2, 0, 2));
  } catch (const WidgetError& e) {
    EXPECT_NE(std::string(e.what()).find("does not fit"), std::string::npos) << e.what();
  }
}

TEST(Cell, RestFramesFollowTheSpec) {
  const Eigen::Vector3i c(3, 3, 3);
  const Eigen::MatrixX3d grid = unitGrid(c);
  // Face with normal y: x along lattice z (first grid direction), z along +y.
  const CellSpec face = CellSpec::face(0, 0, 0, 1);
  const Eigen::Isometry3d f = cellRestFrame(face, c, rows(grid, cellPointIndices(c, face)));
  EXPECT_TRUE(f.linear().col(0).isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE(f.linear().col(2).isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_TRUE(f.translation().isApprox(Eigen::Vector3d(0.25, 0.0, 0.25)));
  // Edge along y: x = +y.
  const CellSpec edge = CellSpec::edge(2, 0, 1, 1);
  const Eigen::Isometry3d e = cellRestFrame(edge, c, rows(grid, cellPointIndices(c, edge)));
  EXPECT_TRUE(e.linear().col(0).isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_NEAR(e.linear().determinant(), 1.0, 1e-15);
  // Point: lattice axes.
  const CellSpec point = CellSpec::point(1, 1, 1);
  EXPECT_TRUE(cellRestFrame(point, c, rows(grid, cellPointIndices(c, point))).linear().isIdentity());
}

TEST(Cell, RingSlabOfACylindricalLatticeHasItsNormalAlongTheAxis) {
  // Slab k of a (radial 2, angular 12, height 3) lattice is a closed ring: its radial and angular
  // sums vanish, and the frame once followed round-off. Its z must be the grid normal
  // radial x angular = +z (so a ring's rotate widget turns counter-clockwise seen from +z).
  const Eigen::Vector3i c(2, 12, 3);
  Eigen::MatrixX3d grid(c.prod(), 3);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 2; ++i) {
        const double t = 2.0 * std::numbers::pi * (j - 1) / 12.0, r = 0.2 + 0.5 * i;
        grid.row(i + 2 * (j + 12 * k)) << r * std::cos(t), r * std::sin(t), 0.4 * k;
      }
  for (int k = 0; k < 3; ++k) {
    const CellSpec ring = CellSpec::slab(2, k);
    const Eigen::Isometry3d f = cellRestFrame(ring, c, rows(grid, cellPointIndices(c, ring)));
    EXPECT_LE((f.linear().col(2) - Eigen::Vector3d::UnitZ()).norm(), 1e-12) << k;
    EXPECT_LE((f.linear().col(0) - Eigen::Vector3d::UnitX()).norm(), 1e-12) << k;
    EXPECT_LE((f.translation() - Eigen::Vector3d(0, 0, 0.4 * k)).norm(), 1e-12) << k;
  }
}

TEST(Cell, FitRecoversARigidMotionAndPerAxisScale) {
  const Eigen::Vector3i c(3, 3, 3);
  const Eigen::MatrixX3d grid = unitGrid(c);
  for (const CellSpec& spec : {CellSpec::face(0, 1, 0, 0), CellSpec::slab(2, 1), CellSpec::box(1, 0, 1)}) {
    const Eigen::MatrixX3d rest = rows(grid, cellPointIndices(c, spec));
    const Eigen::Isometry3d frame = cellRestFrame(spec, c, rest);
    CellAffine truth;
    truth.translation = Eigen::Vector3d(0.1, -0.2, 0.3);
    truth.rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    truth.scale = Eigen::Vector3d(1.5, 0.5, spec.kind == CellKind::Box ? 2.0 : 1.0);
    const Eigen::Affine3d a = truth.matrix(frame);
    const Eigen::MatrixX3d moved = (rest * a.linear().transpose()).rowwise() + a.translation().transpose();
    const CellAffine fit = fitCellAffine(spec, frame, rest, moved);
    EXPECT_TRUE(fit.translation.isApprox(truth.translation, 1e-12)) << cellKindName(spec.kind);
    EXPECT_TRUE(fit.rotation.isApprox(truth.rotation, 1e-12)) << cellKindName(spec.kind);
    EXPECT_TRUE(fit.scale.isApprox(truth.scale, 1e-12)) << cellKindName(spec.kind) << fit.scale.transpose();
  }
}

TEST(Cell, EdgeFitIsTheMinimalRotationAndLengthRatio) {
  const Eigen::Vector3i c(2, 2, 2);
  const Eigen::MatrixX3d grid = unitGrid(c);
  const CellSpec spec = CellSpec::edge(0, 0, 0, 0);
  const Eigen::MatrixX3d rest = rows(grid, cellPointIndices(c, spec));
  Eigen::MatrixX3d moved(2, 3);
  moved << 0, 0, 0, 0, 2, 0;  // turned +90 degrees about z and doubled
  const CellAffine fit = fitCellAffine(spec, cellRestFrame(spec, c, rest), rest, moved);
  EXPECT_TRUE(fit.rotation.isApprox(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix(), 1e-12));
  EXPECT_NEAR(fit.scale.x(), 2.0, 1e-15);
  EXPECT_TRUE(fit.translation.isApprox(Eigen::Vector3d(-0.5, 1.0, 0.0)));
}

TEST(Cell, MasksAndNamesRoundTrip) {
  for (CellKind k : {CellKind::Point, CellKind::Edge, CellKind::Face, CellKind::Slab, CellKind::Box, CellKind::Custom})
    EXPECT_EQ(parseCellKind(cellKindName(k)), k);
  EXPECT_EQ(defaultAttachmentMask(CellKind::Point), AffineMask::t());
  EXPECT_EQ(defaultAttachmentMask(CellKind::Face), AffineMask::tr());
  EXPECT_EQ(parseMask("TRS"), AffineMask::trs());
  EXPECT_EQ(parseMask("RT"), AffineMask::tr());
  EXPECT_EQ(parseMask(""), AffineMask::none());
  EXPECT_FALSE(parseMask("TT").has_value());
  EXPECT_FALSE(parseMask("X").has_value());
  EXPECT_EQ(maskString(AffineMask::tr()), "TR");
}

}  // namespace
}  // namespace ffdkit::widgets
