// The worked examples of Kuriyama 1996, sec. 6.5 (Figs. 6-8 to 6-11), reproduced numerically.
#include <cmath>
#include <complex>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "ffdkit/ffd/cylindrical_lattice.h"
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

  // The widgets keep their place on their cells (Kuriyama 1996, sec. 6.2.1): the ring stays at the face centroid,
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

// FFD of world points through the lattices in pipeline order (Kuriyama 1996, sec. 6.2.3): each lattice embeds
// the previous output in its current rest lattice.
Eigen::MatrixX3d runPipeline(const WidgetModel& m, const std::vector<WidgetId>& order, Eigen::MatrixX3d points) {
  for (WidgetId id : order) {
    const ffd::Lattice lattice = m.ffdLattice(id);
    ffd::Deformer deformer(ffd::embed(lattice, points));
    points = deformer.deform(lattice, points);
  }
  return points;
}

// Independent FFD of a 2x2x2 Bernstein lattice: trilinear interpolation of its 8 local control
// points (Kuriyama 1996, eq. (6.1) with B_0(t) = 1 - t, B_1(t) = t), flat index i + 2 (j + 2 k).
Eigen::Vector3d trilinear(const Eigen::MatrixX3d& p, const Eigen::Vector3d& uvw) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const double b = (i ? uvw[0] : 1 - uvw[0]) * (j ? uvw[1] : 1 - uvw[1]) * (k ? uvw[2] : 1 - uvw[2]);
        x += b * p.row(i + 2 * (j + 2 * k)).transpose();
      }
  return x;
}

// One lattice of the pipeline, computed by hand: a 2x2x2 lattice whose rest points are the unit
// box in its local frame, so the embedding of a world point q is frame^-1 q; points outside the
// (epsilon-grown) box are left unchanged (the default Identity policy, Kuriyama 1996, sec. 6.3.2).
Eigen::Vector3d handFfd(const Eigen::Affine3d& frame, const Eigen::MatrixX3d& local, const Eigen::Vector3d& q,
                        bool* inside = nullptr) {
  const Eigen::Vector3d uvw = frame.inverse() * q;
  const bool in = (uvw.array() >= -1e-9).all() && (uvw.array() <= 1.0 + 1e-9).all();
  if (inside) *inside = in;
  return in ? Eigen::Vector3d(frame * trilinear(local, uvw)) : q;
}

// Fig. 6-9: a 2x2x2 lattice whose top face carries a child lattice; point widgets bound to
// each other and edge widgets of the two lattices bound. The expectations are written from the
// widget semantics (Kuriyama 1996, sec. 6.2) and a hand-made trilinear FFD; they hold wherever the child sits
// on the face (only its start frame is read from the fixture).
TEST(ThesisFigure6_9, ParentFaceCarriesTheChildLattice) {
  Fig69 fig = buildFig69();
  WidgetModel& m = fig.model;
  EXPECT_EQ(m.pipelineOrder(), (std::vector<WidgetId>{fig.parent, fig.child}));
  EXPECT_EQ(m.parentLattice(fig.child), fig.parent);
  const Eigen::MatrixX3d parentRest = m.restPoints(fig.parent);
  const Eigen::MatrixX3d childRest = m.restPoints(fig.child);
  const Eigen::Affine3d childFrame0 = m.latticeFrame(fig.child);
  // The fixture's parent is the unit box at the origin; the child is a box lattice in its frame.
  for (Eigen::Index r = 0; r < 8; ++r) {
    const Eigen::Vector3d corner(r & 1, (r >> 1) & 1, (r >> 2) & 1);
    ASSERT_LE((parentRest.row(r).transpose() - corner).norm(), 1e-15);
    ASSERT_LE((childRest.row(r).transpose() - corner).norm(), 1e-15);
  }

  // Lifting the top face by 0.3 (translate widget along +z): parent points 4..7 rise by 0.3, the
  // others stay; the child (bound with mask {T, R, S} to a face that only translated) is carried
  // up by the same 0.3, its own control points untouched.
  m.applyVariation(fig.faceLift, 0.3);
  Eigen::MatrixX3d parentExpected = parentRest;
  parentExpected.bottomRows(4).col(2).array() += 0.3;
  EXPECT_LE((m.controlPoints(fig.parent) - parentExpected).cwiseAbs().maxCoeff(), 1e-14);
  const Eigen::Affine3d childFrame1 = Eigen::Translation3d(0, 0, 0.3) * childFrame0;
  EXPECT_LE((m.latticeFrame(fig.child).matrix() - childFrame1.matrix()).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LE((m.controlPoints(fig.child) - childRest).cwiseAbs().maxCoeff(), 0.0);

  // Point widgets bound (gain 1), attached pointing -x and +x: the corners spread symmetrically.
  m.applyVariation(fig.pointA, 0.1);
  EXPECT_DOUBLE_EQ(m.variation(fig.pointB), 0.1);
  parentExpected(0, 0) = -0.1;
  parentExpected(1, 0) = 1.1;
  EXPECT_LE((m.controlPoints(fig.parent) - parentExpected).cwiseAbs().maxCoeff(), 1e-14);

  // Edge widgets of different lattices bound, both pointing +y in the world: dragging the child's
  // edge (0,0,0)/x by 0.08 moves its points 0 and 1 by 0.08 along world y, and through the binding
  // the parent's edge (0,1,0)/x (points 2 and 3) by the same 0.08.
  m.applyVariation(fig.childEdge, 0.08);
  EXPECT_DOUBLE_EQ(m.variation(fig.parentEdge), 0.08);
  parentExpected(2, 1) += 0.08;
  parentExpected(3, 1) += 0.08;
  EXPECT_LE((m.controlPoints(fig.parent) - parentExpected).cwiseAbs().maxCoeff(), 1e-14);
  Eigen::MatrixX3d childWorldExpected(8, 3);
  for (Eigen::Index r = 0; r < 8; ++r) {
    Eigen::Vector3d x = childFrame1 * Eigen::Vector3d(childRest.row(r).transpose());
    if (r < 2) x.y() += 0.08;
    childWorldExpected.row(r) = x.transpose();
  }
  EXPECT_LE((m.worldControlPoints(fig.child) - childWorldExpected).cwiseAbs().maxCoeff(), 1e-14);
  // The child's frame did not move (the parent's top face did not).
  EXPECT_LE((m.latticeFrame(fig.child).matrix() - childFrame1.matrix()).cwiseAbs().maxCoeff(), 1e-14);

  // FFD output of the pipeline (pre-order: parent, then child in its moved rest box) against the
  // hand computation, on points spread over both lattices and around them.
  std::mt19937 rng(69);
  std::uniform_real_distribution<double> U(-0.2, 1.2), Z(-0.2, 2.0);
  Eigen::MatrixX3d q(400, 3);
  std::uniform_real_distribution<double> onFace(0.0, 1.0);
  for (Eigen::Index r = 0; r < q.rows(); ++r) q.row(r) << U(rng), U(rng), Z(rng);
  // A quarter on the parent's rest top face z = 1, which the parent lifts onto the face carrying
  // the child: the points where parent-then-child differs from child-then-parent.
  for (Eigen::Index r = 0; r < q.rows(); r += 4) q.row(r) << onFace(rng), onFace(rng), 1.0;
  const Eigen::MatrixX3d childLocal = m.controlPoints(fig.child);
  const Eigen::MatrixX3d pipeline = runPipeline(m, m.pipelineOrder(), q);
  int inParent = 0, inChild = 0;
  for (Eigen::Index r = 0; r < q.rows(); ++r) {
    bool a = false, b = false;
    const Eigen::Vector3d afterParent = handFfd(Eigen::Affine3d::Identity(), parentExpected, q.row(r).transpose(), &a);
    const Eigen::Vector3d expected = handFfd(childFrame1, childLocal, afterParent, &b);
    inParent += a;
    inChild += b;
    EXPECT_LE((pipeline.row(r).transpose() - expected).norm(), 1e-12) << "point " << r;
  }
  EXPECT_GT(inParent, 50);  // both lattices really deformed some points
  EXPECT_GT(inChild, 5);
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

// Fig. 6-11: EFFD. A cylindrical lattice (2 radial x 12 angular x 4 height points, cubic
// periodic angle, cubic height) around the z axis; rotate widgets on the rings k = 1, 2, 3 turn
// them by phi_k = k pi / 6 (the top drives the others with gains 2/3 and 1/3), as in the
// cylinder-twist sample scene.
// Closed form: the rest point (r_i cos t_j, r_i sin t_j, z_k) is separable, so a rest point with
// in-plane part y (a complex number) and height parameter w maps to
//   y' = y * sum_k B_k(w) e^(i phi_k) = y * ((1 - w) + w e^(i pi / 6))^3,   z' = z,
// since the clamped cubic on 4 points is the cubic Bernstein basis and Greville heights make
// w = (z - zMin) / (zMax - zMin). The twist angle is 3 atan2(w sin(pi/6), 1 - w + w cos(pi/6)):
// 0 at the bottom, pi/4 at mid-height, pi/2 at the top.
TEST(ThesisFigure6_11, CylindricalLatticeTwistsByTheClosedFormAngle) {
  ffd::CylindricalLatticeOptions cylinder;
  cylinder.counts = {2, 12, 4};
  cylinder.bases = {ffd::AxisBasis::bspline(1), ffd::AxisBasis::periodic(3), ffd::AxisBasis::bspline(3)};
  cylinder.outerRadius = 0.7;
  cylinder.zMin = -0.55;
  cylinder.zMax = 0.55;
  const ffd::Lattice restLattice = ffd::makeCylindricalLattice(cylinder);
  WidgetModel m;
  LatticeOptions options;
  options.name = "cylinder-lattice";
  options.counts = cylinder.counts;
  options.restPoints = restLattice.restPoints();
  options.settings.basis = cylinder.bases;
  options.settings.cylinder = restLattice.cylinderRestShape();
  const WidgetId lattice = m.addLattice(options);
  std::vector<WidgetId> turns;
  for (int k = 1; k <= 3; ++k) turns.push_back(m.addAffine(m.addCell(lattice, CellSpec::slab(2, k)), AffineKind::Rotate));
  m.bind(turns[2], turns[1], ConversionRule(2.0 / 3.0));
  m.bind(turns[2], turns[0], ConversionRule(1.0 / 3.0));

  std::mt19937 rng(611);
  std::uniform_real_distribution<double> radius(0.0, 0.45), angle(-pi, pi), height(-0.55, 0.55);
  Eigen::MatrixX3d q(300, 3);
  for (Eigen::Index r = 0; r < q.rows(); ++r) {
    const double a = angle(rng), rr = r < 3 ? 0.0 : radius(rng);
    // Three points on the axis; three at the bottom, middle and top heights exactly.
    const double z = r % 100 == 3 ? -0.55 : r % 100 == 4 ? 0.0 : r % 100 == 5 ? 0.55 : height(rng);
    q.row(r) << rr * std::cos(a), rr * std::sin(a), z;
  }
  ffd::Lattice ffdLattice = m.ffdLattice(lattice);
  ffd::Deformer deformer(ffd::embed(ffdLattice, q));
  ASSERT_EQ(deformer.embedding().insideCount(), q.rows());

  m.setVariation(turns[2], pi / 2);
  ffdLattice.setControlPoints(m.controlPoints(lattice));  // the lattice frame is the identity
  const Eigen::MatrixX3d out = deformer.deform(ffdLattice, q);
  const std::complex<double> step = std::polar(1.0, pi / 6);
  for (Eigen::Index r = 0; r < q.rows(); ++r) {
    const double w = (q(r, 2) - cylinder.zMin) / (cylinder.zMax - cylinder.zMin);
    const std::complex<double> factor = std::pow((1.0 - w) + w * step, 3);
    const std::complex<double> y(q(r, 0), q(r, 1)), expected = factor * y;
    EXPECT_NEAR(out(r, 0), expected.real(), 1e-10) << "point " << r;
    EXPECT_NEAR(out(r, 1), expected.imag(), 1e-10) << "point " << r;
    EXPECT_NEAR(out(r, 2), q(r, 2), 1e-10) << "point " << r;
    if (std::abs(y) > 0.05) {
      // The twist angle itself, point by point.
      const double twist = std::arg(std::complex<double>(out(r, 0), out(r, 1)) / y);
      EXPECT_NEAR(twist, 3.0 * std::atan2(w * std::sin(pi / 6), 1.0 - w + w * std::cos(pi / 6)), 1e-9) << "point " << r;
    }
  }
  // Spot values: bottom unturned, mid-height pi/4 with radius factor cos^3(pi/12), top pi/2.
  for (Eigen::Index r : {103, 104, 105}) {
    const std::complex<double> ratio = std::complex<double>(out(r, 0), out(r, 1)) / std::complex<double>(q(r, 0), q(r, 1));
    const double expectAngle = r == 103 ? 0.0 : r == 104 ? pi / 4 : pi / 2;
    const double expectRadius = r == 104 ? std::pow(std::cos(pi / 12), 3) : 1.0;
    EXPECT_NEAR(std::arg(ratio), expectAngle, 1e-9) << r;
    EXPECT_NEAR(std::abs(ratio), expectRadius, 1e-9) << r;
  }
}

}  // namespace
}  // namespace ffdkit::widgets
