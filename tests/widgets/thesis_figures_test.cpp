// The worked examples of seed 001 ch. 6 (spec §9), reproduced numerically.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "ffdkit/ffd/deformer.h"
#include "ffdkit/ffd/embedding.h"
#include "ffdkit/widgets/widget_model.h"
#include "ffdkit/widgets/thesis_examples.h"

namespace ffdkit::widgets {
namespace {

using std::numbers::pi;

Eigen::Vector3d row(const Eigen::MatrixX3d& m, Eigen::Index r) { return m.row(r).transpose(); }

// Fig. 6-2: in the unit box, a face's rotate widget turned 5 degrees about +z, an edge's
// translate widget moved +0.5 along x, a point's translate widget +0.25 along z.
TEST(ThesisFigure6_2, ExactControlPoints) {
  Fig62 fig = buildFig62();
  WidgetModel& m = fig.model;
  const Eigen::MatrixX3d rest = m.restPoints(fig.lattice);
  m.applyVariation(fig.faceRotate, 5.0 * pi / 180.0);
  m.applyVariation(fig.edgeTranslate, 0.5);
  m.applyVariation(fig.pointTranslate, 0.25);

  Eigen::MatrixX3d expected = rest;
  const double c = std::cos(5.0 * pi / 180.0), s = std::sin(5.0 * pi / 180.0);
  // Face (i, j in {0, 1}, k = 2) about its centroid (0.25, 0.25, 1), counter-clockwise from +z.
  for (Eigen::Index idx : {18, 19, 22, 21}) {
    const double x = rest(idx, 0) - 0.25, y = rest(idx, 1) - 0.25;
    expected.row(idx) << 0.25 + c * x - s * y, 0.25 + s * x + c * y, 1.0;
  }
  expected(6, 0) += 0.5;   // edge (0,2,0)-(1,2,0)
  expected(7, 0) += 0.5;
  expected(8, 2) += 0.25;  // point (2,2,0)
  EXPECT_LE((m.controlPoints(fig.lattice) - expected).cwiseAbs().maxCoeff(), 1e-15);
  // Spot values written out by hand: (0,0,1) turns to (0.25 - 0.25c + 0.25s, 0.25 - 0.25s - 0.25c, 1).
  EXPECT_NEAR(m.controlPoints(fig.lattice)(18, 0), 0.25 - 0.25 * c + 0.25 * s, 1e-15);
  EXPECT_NEAR(m.controlPoints(fig.lattice)(18, 1), 0.25 - 0.25 * s - 0.25 * c, 1e-15);
  EXPECT_DOUBLE_EQ(m.controlPoints(fig.lattice)(6, 0), 0.5);
  EXPECT_DOUBLE_EQ(m.controlPoints(fig.lattice)(8, 2), 0.25);

  // The widgets keep their place on their cells (l.2266): the ring stays at the face centroid,
  // turned with it; the arrow moved with its edge.
  const WidgetFrame ring = m.affineFrame(fig.faceRotate);
  EXPECT_TRUE(ring.frame.translation().isApprox(Eigen::Vector3d(0.25, 0.25, 1.0), 1e-14));
  EXPECT_NEAR(ring.frame.linear().col(0).dot(Eigen::Vector3d(c, s, 0)), 1.0, 1e-14);
  EXPECT_TRUE(m.affineFrame(fig.edgeTranslate).frame.translation().isApprox(Eigen::Vector3d(0.75, 1.0, 0.0), 1e-14));
  EXPECT_DOUBLE_EQ(m.variation(fig.edgeTranslate), 0.5);
}

// Fig. 6-8: a 2x3x2 lattice; translate and rotate widgets on two faces, translate widgets in
// opposite directions on two edges, each pair bound: the deformation is mirror-symmetric.
TEST(ThesisFigure6_8, BoundOppositeWidgetsDeformMirrorSymmetrically) {
  Fig68 fig = buildFig68();
  WidgetModel& m = fig.model;
  m.applyVariation(fig.faceTranslateA, 0.2);
  m.applyVariation(fig.faceRotateB, 0.3);  // driven from the other side this time
  m.applyVariation(fig.edgeTranslateA, 0.15);
  m.applyVariation(fig.faceRotateA, -0.12);
  m.applyVariation(fig.edgeTranslateB, 0.05);
  m.applyVariation(fig.faceTranslateB, -0.07);

  const Eigen::MatrixX3d p = m.controlPoints(fig.lattice);
  const Eigen::MatrixX3d rest = m.restPoints(fig.lattice);
  EXPECT_GT((p - rest).cwiseAbs().maxCoeff(), 0.1);  // it did deform
  double worst = 0.0;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 2; ++i) {
        const Eigen::Index a = i + 2 * (j + 3 * k), b = i + 2 * ((2 - j) + 3 * k);
        Eigen::Vector3d mirrored = row(p, b);
        mirrored.y() = 1.0 - mirrored.y();  // reflect about the middle plane y = 0.5
        worst = std::max(worst, (row(p, a) - mirrored).cwiseAbs().maxCoeff());
      }
  EXPECT_LE(worst, 1e-12);
  EXPECT_DOUBLE_EQ(m.variation(fig.edgeTranslateB), m.variation(fig.edgeTranslateA));
}

// FFD of world points through the lattices in pipeline order (spec §6): each lattice embeds
// the previous output in its current rest lattice.
Eigen::MatrixX3d runPipeline(const WidgetModel& m, const std::vector<WidgetId>& order, Eigen::MatrixX3d points) {
  for (WidgetId id : order) {
    const ffd::Lattice lattice = m.ffdLattice(id);
    ffd::Deformer deformer(ffd::embed(lattice, points));
    points = deformer.deform(lattice, points);
  }
  return points;
}

// Fig. 6-9: a 2x2x2 lattice whose top face carries a child lattice; point widgets bound to
// each other and edge widgets of the two lattices bound.
TEST(ThesisFigure6_9, ParentFaceCarriesTheChildLattice) {
  Fig69 fig = buildFig69();
  WidgetModel& m = fig.model;
  EXPECT_EQ(m.pipelineOrder(), (std::vector<WidgetId>{fig.parent, fig.child}));
  EXPECT_EQ(m.parentLattice(fig.child), fig.parent);
  const Eigen::MatrixX3d childWorld0 = m.worldControlPoints(fig.child);

  m.applyVariation(fig.faceLift, 0.3);
  // The child lattice rode up with the face, undeformed.
  const Eigen::MatrixX3d lifted = childWorld0.rowwise() + Eigen::RowVector3d(0, 0, 0.3);
  EXPECT_LE((m.worldControlPoints(fig.child) - lifted).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LE((m.controlPoints(fig.child) - m.restPoints(fig.child)).cwiseAbs().maxCoeff(), 0.0);

  // Point widgets bound: both points move along their own axes.
  m.applyVariation(fig.pointA, 0.1);
  EXPECT_DOUBLE_EQ(m.variation(fig.pointB), 0.1);
  // Edge widgets of different lattices bound: dragging the child's edge moves the parent's too.
  m.applyVariation(fig.childEdge, 0.08);
  EXPECT_DOUBLE_EQ(m.variation(fig.parentEdge), 0.08);
  EXPECT_GT((m.controlPoints(fig.child) - m.restPoints(fig.child)).cwiseAbs().maxCoeff(), 0.07);

  // FFD output: the pipeline in pre-order equals parent-then-child composition.
  Eigen::MatrixX3d q(6, 3);
  // Points on the parent's top face land on the child's bottom after the parent: order matters.
  q << 0.5, 0.5, 0.5, 0.2, 0.8, 0.9, 0.4, 0.6, 1.0, 0.4, 0.6, 1.5, 0.9, 0.1, 0.2, 0.5, 0.5, 1.0;
  const Eigen::MatrixX3d pipeline = runPipeline(m, m.pipelineOrder(), q);
  const Eigen::MatrixX3d composed = runPipeline(m, {fig.child}, runPipeline(m, {fig.parent}, q));
  EXPECT_LE((pipeline - composed).cwiseAbs().maxCoeff(), 0.0);
  const Eigen::MatrixX3d reversed = runPipeline(m, {fig.child, fig.parent}, q);
  EXPECT_GT((pipeline - reversed).cwiseAbs().maxCoeff(), 1e-3);  // the order matters
}

// Fig. 6-10: a press. A free handle (rotate widget) bound to a translate widget on the top face,
// pointing down: one turn lowers the face by the screw's pitch; a clamp range stops it.
TEST(ThesisFigure6_10, PressHandleLowersTheFaceByThePitch) {
  Fig610 fig = buildFig610(/*pitch=*/0.1, std::nullopt);
  WidgetModel& m = fig.model;
  const Eigen::MatrixX3d rest = m.controlPoints(fig.lattice);
  m.applyVariation(fig.handle, 2.0 * pi);
  const Eigen::MatrixX3d p = m.controlPoints(fig.lattice);
  for (Eigen::Index i = 0; i < p.rows(); ++i) {
    const double dz = rest(i, 2) > 0.5 ? -0.1 : 0.0;  // top face down by the pitch, bottom fixed
    EXPECT_NEAR(p(i, 2), rest(i, 2) + dz, 1e-15) << i;
    EXPECT_NEAR(p(i, 0), rest(i, 0), 1e-15);
  }
  EXPECT_NEAR(m.variation(fig.press), 0.1, 1e-15);
}

TEST(ThesisFigure6_10, ClampRangeStopsTheJaw) {
  Fig610 fig = buildFig610(0.1, VariationRange{0.0, 0.15});
  WidgetModel& m = fig.model;
  m.beginGesture(fig.handle);
  m.updateGesture(2.0 * pi);
  EXPECT_NEAR(m.variation(fig.press), 0.1, 1e-15);
  m.updateGesture(6.0 * pi);  // three turns would be 0.3
  EXPECT_NEAR(m.variation(fig.press), 0.15, 1e-15);
  EXPECT_NEAR(m.controlPoints(fig.lattice)(4, 2), 1.0 - 0.15, 1e-15);
  m.updateGesture(-2.0 * pi);  // back the other way: stops at 0
  EXPECT_NEAR(m.variation(fig.press), 0.0, 1e-15);
  m.endGesture();
  EXPECT_NEAR(m.variation(fig.handle), -2.0 * pi, 1e-15);  // the handle itself is free
}

}  // namespace
}  // namespace ffdkit::widgets
