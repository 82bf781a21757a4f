// Make Cell from selected points (app/interaction/cell_from_selection.h): each kind from its own
// points (in any order), the specs written out by hand, and selections that do not fit a kind
// with the reason why.
#include <gtest/gtest.h>

#include "ffdkit/interaction/cell_from_selection.h"
#include "edit_test_document.h"

namespace ffdkit::app {
namespace {
using test::f;

using widgets::CellKind;
using widgets::CellSpec;
using Indices = std::vector<Eigen::Index>;

const Eigen::Vector3i n333(3, 3, 3);

TEST(CellFromSelection, EachKindFromItsPoints) {
  EXPECT_EQ(classifySelection(n333, {f(2, 2, 0)}), CellSpec::point(2, 2, 0));
  EXPECT_EQ(classifySelection(n333, {f(1, 2, 0), f(0, 2, 0)}), CellSpec::edge(0, 2, 0, 0));
  EXPECT_EQ(classifySelection(n333, {f(1, 1, 1), f(1, 1, 2)}), CellSpec::edge(1, 1, 1, 2));
  // Fig. 6-2's face: the quad (0..1, 0..1) in the plane k = 2.
  EXPECT_EQ(classifySelection(n333, {f(1, 1, 2), f(0, 0, 2), f(1, 0, 2), f(0, 1, 2)}), CellSpec::face(0, 0, 2, 2));
  EXPECT_EQ(classifySelection(n333, {f(2, 1, 1), f(2, 2, 1), f(2, 1, 2), f(2, 2, 2)}), CellSpec::face(2, 1, 1, 0));
  Indices box, plane;
  for (int k = 1; k <= 2; ++k)
    for (int j = 0; j <= 1; ++j)
      for (int i = 1; i <= 2; ++i) box.push_back(f(i, j, k));
  EXPECT_EQ(classifySelection(n333, box), CellSpec::box(1, 0, 1));
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) plane.push_back(f(i, 2, k));
  EXPECT_EQ(classifySelection(n333, plane), CellSpec::slab(1, 2));
  // Anything else is no kind: the application asks about a custom cell.
  EXPECT_FALSE(classifySelection(n333, {f(0, 0, 0), f(2, 0, 0)}).has_value());
  EXPECT_FALSE(classifySelection(n333, {f(0, 0, 0), f(1, 0, 0), f(2, 0, 0)}).has_value());
  EXPECT_FALSE(classifySelection(n333, {}).has_value());
  const auto custom = cellFromSelection(n333, {f(0, 0, 0), f(2, 0, 0)}, CellKind::Custom);
  ASSERT_TRUE(custom.spec.has_value());
  EXPECT_EQ(custom.spec->indices, (Indices{f(0, 0, 0), f(2, 0, 0)}));
}

TEST(CellFromSelection, AFourPointPlaneOfA2x2LatticeIsAFaceFirstAndASlabWhenAsked) {
  const Eigen::Vector3i n(2, 2, 3);
  const Indices top{8, 9, 10, 11};  // k = 2
  EXPECT_EQ(classifySelection(n, top), CellSpec::face(0, 0, 2, 2));
  EXPECT_EQ(cellFromSelection(n, top, CellKind::Slab).spec, CellSpec::slab(2, 2));
}

TEST(CellFromSelection, ASelectionThatDoesNotFitSaysWhy) {
  auto why = [](const Indices& indices, CellKind kind) {
    const auto r = cellFromSelection(n333, indices, kind);
    EXPECT_FALSE(r.spec.has_value());
    return r.why;
  };
  EXPECT_EQ(why({f(0, 0, 0), f(1, 0, 0)}, CellKind::Point), "a point cell is 1 point; 2 points are selected");
  EXPECT_EQ(why({f(0, 0, 0), f(2, 0, 0)}, CellKind::Edge),
            "an edge cell is 2 neighbouring points along one axis; (0,0,0) and (2,0,0) differ by 2 along i");
  EXPECT_EQ(why({f(0, 0, 0), f(1, 1, 0)}, CellKind::Edge),
            "an edge cell is 2 neighbouring points along one axis; (0,0,0) and (1,1,0) differ by 1 along i, 1 along j");
  EXPECT_EQ(why({f(0, 0, 0), f(2, 0, 0), f(0, 1, 0), f(2, 1, 0)}, CellKind::Face),
            "a face cell is the 4 corners of one grid quad (one step along two axes, one plane); the points span "
            "(0,0,0) to (2,1,0)");
  EXPECT_EQ(why({f(0, 0, 0)}, CellKind::Box), "a box cell is the 8 corners of one grid hexahedron; 1 point is selected");
  EXPECT_EQ(why({f(0, 0, 2), f(1, 0, 2)}, CellKind::Slab),
            "a slab cell is every point of one index plane: plane j = 0 has 9 points and 2 points are selected");
  EXPECT_EQ(why({}, CellKind::Face), "no point is selected");
  EXPECT_THROW(cellFromSelection(n333, {27}, CellKind::Point), std::invalid_argument);
  EXPECT_THROW(cellFromSelection(n333, {3, 3}, CellKind::Custom), std::invalid_argument);
}

TEST(CellFromSelection, RotateAndScaleOnAPointCellAreRefusedWithAReason) {
  EXPECT_FALSE(affineRefusal(widgets::AffineKind::Translate, CellKind::Point).has_value());
  EXPECT_FALSE(affineRefusal(widgets::AffineKind::Rotate, CellKind::Edge).has_value());
  const auto why = affineRefusal(widgets::AffineKind::Rotate, CellKind::Point);
  ASSERT_TRUE(why.has_value());
  EXPECT_NE(why->find("moves nothing"), std::string::npos);
  EXPECT_TRUE(affineRefusal(widgets::AffineKind::Scale, CellKind::Point).has_value());
}

}  // namespace
}  // namespace ffdkit::app
