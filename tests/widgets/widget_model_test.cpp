#include "ffdkit/widgets/widget_model.h"

#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "ffdkit/widgets/thesis_examples.h"
#include "ffdkit/widgets/widget_error.h"
#include "widget_test_support.h"

namespace ffdkit::widgets {
namespace {

using std::numbers::pi;

Eigen::Affine3d pointing(const Eigen::Vector3d& direction, const Eigen::Vector3d& offset = Eigen::Vector3d::Zero()) {
  Eigen::Affine3d a = Eigen::Affine3d::Identity();
  a.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitX(), direction).toRotationMatrix();
  a.translation() = offset;
  return a;
}

using testing::expectError;

// The README example: a 3x3x3 lattice, a rotate widget on the top face bound to a translate
// widget, turned by 90 degrees.
TEST(WidgetModel, ScriptingExampleFromTheReadme) {
  WidgetModel model;
  const WidgetId box = model.addLattice("box", Eigen::Vector3i(3, 3, 3));
  const WidgetId top = model.addCell(box, CellSpec::slab(/*normalAxis=*/2, /*planeIndex=*/2), "top");
  const WidgetId knob = model.addAffine(top, AffineKind::Rotate, "knob");
  const WidgetId side = model.addCell(box, CellSpec::face(0, 0, 0, /*normalAxis=*/0), "side");
  const WidgetId push = model.addAffine(side, AffineKind::Translate, "push");
  model.bind(knob, push, ConversionRule(0.1));  // 0.1 units per radian
  model.applyVariation(model.find("knob"), pi / 2);

  const Eigen::MatrixX3d p = model.controlPoints(box);
  // Top slab turned 90 degrees about its centre (0.5, 0.5, 1): (0, 0, 1) -> (1, 0, 1).
  EXPECT_TRUE(p.row(18).isApprox(Eigen::RowVector3d(1, 0, 1), 1e-14));
  // Side face (normal x, x axis = lattice y) pushed 0.1 * pi/2 along +y.
  EXPECT_NEAR(p(0, 1), 0.1 * pi / 2, 1e-15);
  EXPECT_NEAR(model.variation(push), 0.1 * pi / 2, 1e-15);
}

TEST(WidgetModel, IdsNamesAndTypes) {
  Fig62 fig = buildFig62();
  const WidgetModel& m = fig.model;
  EXPECT_EQ(m.find("red-ring"), fig.faceRotate);
  EXPECT_EQ(m.type(fig.face), WidgetType::Cell);
  EXPECT_EQ(m.attachedCell(fig.faceRotate), fig.face);
  EXPECT_EQ(m.affinesOf(fig.face), std::vector<WidgetId>{fig.faceRotate});
  EXPECT_EQ(m.latticeOf(fig.pointTranslate), fig.lattice);
  EXPECT_EQ(toString(fig.lattice), "w0");
  EXPECT_EQ(parseWidgetId("w12"), WidgetId{12});
  EXPECT_FALSE(parseWidgetId("w012").has_value());
  EXPECT_FALSE(parseWidgetId("x1").has_value());
  EXPECT_EQ(m.glyph(fig.faceRotate).shape, "ring");
  EXPECT_EQ(m.bindings().size(), 3u);  // three attachments
}

TEST(WidgetModel, BadInputGivesClearErrorsAndChangesNothing) {
  Fig62 fig = buildFig62();
  WidgetModel& m = fig.model;
  const WidgetModelData before = m.toData();
  const std::uint64_t revision = m.revision();

  auto e = expectError(WidgetErrorCode::UnknownWidget, [&] { m.applyVariation(WidgetId{99}, 1.0); });
  EXPECT_NE(std::string(e.what()).find("unknown widget 'w99' (known: w0, w1"), std::string::npos) << e.what();
  e = expectError(WidgetErrorCode::UnknownWidget, [&] { m.find("nope"); });
  EXPECT_NE(std::string(e.what()).find("red-ring"), std::string::npos) << e.what();
  e = expectError(WidgetErrorCode::InvalidBinding, [&] { m.bind(fig.faceRotate, fig.faceRotate); });
  EXPECT_NE(std::string(e.what()).find("itself"), std::string::npos);
  expectError(WidgetErrorCode::InvalidArgument, [&] { m.bind(fig.faceRotate, fig.edgeTranslate, ConversionRule(0.0)); });
  expectError(WidgetErrorCode::InvalidArgument,
              [&] { m.bind(fig.faceRotate, fig.edgeTranslate, ConversionRule(1.0, VariationRange{1, 0})); });
  expectError(WidgetErrorCode::InvalidBinding, [&] { m.bind(fig.lattice, fig.faceRotate); });
  expectError(WidgetErrorCode::InvalidBinding, [&] { m.bind(fig.edge, fig.faceRotate); });  // already attached
  expectError(WidgetErrorCode::InvalidBinding, [&] { m.bind(fig.face, fig.lattice); });     // own ancestor
  expectError(WidgetErrorCode::InvalidArgument, [&] { m.addCell(fig.lattice, CellSpec::edge(2, 0, 0, 0)); });
  expectError(WidgetErrorCode::InvalidArgument, [&] { m.addLattice("", Eigen::Vector3i(1, 4, 4)); });
  expectError(WidgetErrorCode::InvalidArgument, [&] { m.addLattice("red-ring", Eigen::Vector3i(2, 2, 2)); });
  expectError(WidgetErrorCode::InvalidArgument, [&] { m.addAffine(fig.lattice, AffineKind::Rotate); });
  expectError(WidgetErrorCode::GestureState, [&] { m.updateGesture(1.0); });
  expectError(WidgetErrorCode::GestureState, [&] { m.endGesture(); });
  expectError(WidgetErrorCode::InvalidArgument, [&] { m.applyVariation(fig.faceRotate, std::nan("")); });
  expectError(WidgetErrorCode::InvalidArgument, [&] { m.applyMotion(fig.faceRotate, Eigen::Affine3d::Identity()); });

  EXPECT_EQ(m.revision(), revision);
  const WidgetModelData after = m.toData();
  EXPECT_EQ(after.bindings, before.bindings);
  EXPECT_EQ(after.affines.size(), before.affines.size());
  EXPECT_EQ(after.lattices.size(), before.lattices.size());
  EXPECT_FALSE(m.gestureActive());
}

TEST(WidgetModel, GestureStateMachine) {
  Fig62 fig = buildFig62();
  WidgetModel& m = fig.model;
  m.beginGesture(fig.edgeTranslate);
  expectError(WidgetErrorCode::GestureState, [&] { m.beginGesture(fig.faceRotate); });
  expectError(WidgetErrorCode::GestureState, [&] { m.bind(fig.faceRotate, fig.edgeTranslate); });
  expectError(WidgetErrorCode::GestureState, [&] { m.updateGesture(Eigen::Affine3d::Identity()); });
  m.updateGesture(0.3);
  m.updateGesture(0.1);  // from the gesture start, not incremental
  EXPECT_NEAR(m.controlPoints(fig.lattice)(6, 0), 0.1, 1e-15);
  m.cancelGesture();
  EXPECT_EQ(m.controlPoints(fig.lattice), m.restPoints(fig.lattice));
  EXPECT_EQ(m.variation(fig.edgeTranslate), 0.0);
}

TEST(WidgetModel, LoopCheck) {
  WidgetModel m;
  const WidgetId lat = m.addLattice("", Eigen::Vector3i(2, 3, 2));
  const WidgetId ea = m.addCell(lat, CellSpec::edge(0, 0, 0, 0));
  const WidgetId eb = m.addCell(lat, CellSpec::edge(0, 2, 0, 0));
  const WidgetId ec = m.addCell(lat, CellSpec::edge(0, 1, 1, 0));
  const WidgetId ta = m.addAffine(ea, AffineKind::Translate, "", pointing(-Eigen::Vector3d::UnitY()));
  const WidgetId tb = m.addAffine(eb, AffineKind::Translate, "", pointing(Eigen::Vector3d::UnitY()));
  const WidgetId tc = m.addAffine(ec, AffineKind::Translate);
  // A mirror pair closed through a third widget: gains -1, -1, 1 multiply to 1: consistent.
  m.bind(ta, tc, ConversionRule(-1.0));
  m.bind(tc, tb, ConversionRule(-1.0));
  const std::size_t count = m.bindings().size();
  const BindingId closing = m.bind(ta, tb);
  EXPECT_EQ(m.bindings().size(), count + 1);
  m.unbind(closing);
  // The same loop with gain 2 is refused, naming the loop.
  auto e = expectError(WidgetErrorCode::InconsistentLoop, [&] { m.bind(ta, tb, ConversionRule(2.0)); });
  const std::string what = e.what();
  EXPECT_NE(what.find("loop " + toString(ta) + " -> " + toString(tb) + " -> " + toString(tc) + " -> " + toString(ta)),
            std::string::npos) << what;
  EXPECT_NE(what.find("multiply to 2"), std::string::npos) << what;
  EXPECT_EQ(m.bindings().size(), count);
  // Changing a rule so that an existing loop breaks is refused too.
  m.bind(ta, tb);
  expectError(WidgetErrorCode::InconsistentLoop, [&] { m.setRule(m.bindingsOf(tc).back(), ConversionRule(3.0)); });

  // Cell loops: equal masks are consistent, different masks are not.
  const WidgetId pa = m.addCell(lat, CellSpec::point(0, 0, 1));
  const WidgetId pb = m.addCell(lat, CellSpec::point(1, 0, 1));
  const WidgetId pc = m.addCell(lat, CellSpec::point(0, 2, 1));
  m.bind(pa, pb, AffineMask::t());
  m.bind(pb, pc, AffineMask::t());
  expectError(WidgetErrorCode::InconsistentLoop, [&] { m.bind(pc, pa, AffineMask::tr()); });
  m.bind(pc, pa, AffineMask::t());
  // A loop through an attachment and a cell binding would move a cell twice: refused.
  expectError(WidgetErrorCode::InconsistentLoop, [&] { m.bind(ea, ec); });
}

TEST(WidgetModel, LoopCheckExaminesEveryRouteNotOnlyTheShortestLoop) {
  WidgetModel m;
  const WidgetId lat = m.addLattice("box", Eigen::Vector3i(3, 3, 3));
  const WidgetId f1 = m.addCell(lat, CellSpec::face(0, 0, 0, 2));
  const WidgetId f2 = m.addCell(lat, CellSpec::face(1, 1, 2, 2));
  const WidgetId a1 = m.addAffine(f1, AffineKind::Translate, "a1");
  const WidgetId b1 = m.addAffine(f1, AffineKind::Rotate, "b1");
  const WidgetId a2 = m.addAffine(f2, AffineKind::Translate, "a2");
  const WidgetId b2 = m.addAffine(f2, AffineKind::Rotate, "b2");
  m.bind(b1, b2);  // the faces' rings turn together
  // A chain of free widgets from a2 back to a1 whose gains multiply to 1/2.
  std::vector<WidgetId> c;
  for (int i = 0; i < 5; ++i) c.push_back(m.addFreeAffine(AffineKind::Translate));
  m.bind(a2, c[0], ConversionRule(2.0));
  for (int i = 0; i + 1 < 5; ++i) m.bind(c[i], c[i + 1]);
  m.bind(c[4], a1);  // harmless: the only loop meets at the two faces
  // a1 <-> a2: the shortest loop (through the faces) is harmless, the one through the chain is not.
  auto e = expectError(WidgetErrorCode::InconsistentLoop, [&] { m.bind(a1, a2); });
  EXPECT_NE(std::string(e.what()).find("two routes that disagree"), std::string::npos) << e.what();
  m.bind(a1, a2, ConversionRule(0.5));  // consistent with the chain
}

TEST(WidgetModel, CellBindingCopiesTheMaskedMotion) {
  WidgetModel m;
  const WidgetId lat = m.addLattice("", Eigen::Vector3i(3, 3, 3));
  const WidgetId a = m.addCell(lat, CellSpec::face(0, 0, 0, 2));
  const WidgetId b = m.addCell(lat, CellSpec::face(1, 1, 2, 2));
  m.bind(a, b, AffineMask::tr());
  const Eigen::Affine3d motion(Eigen::Translation3d(0.1, 0.2, 0.3) * Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()));
  m.applyMotion(a, motion);
  // b: the same translation of its centroid, the same rotation about its own centroid.
  const Eigen::Vector3d ca(0.25, 0.25, 0.0), cb(0.75, 0.75, 1.0);
  const Eigen::Vector3d t = motion * ca - ca;
  const Eigen::MatrixX3d rest = m.restPoints(lat);
  for (Eigen::Index i : m.cellIndices(b)) {
    const Eigen::Vector3d expect = cb + t + motion.linear() * (rest.row(i).transpose() - cb);
    EXPECT_TRUE(m.controlPoints(lat).row(i).transpose().isApprox(expect, 1e-14)) << i;
  }
}

TEST(WidgetModel, HierarchyFollowsAndLatticeDragMovesTheParentCell) {
  Fig69 fig = buildFig69();
  WidgetModel& m = fig.model;
  const Eigen::Affine3d frame0 = m.latticeFrame(fig.child);
  // Dragging the child lattice (two-way) moves the parent's face, and the child follows it.
  m.applyMotion(fig.child, Eigen::Affine3d(Eigen::Translation3d(0, 0, 0.2)));
  EXPECT_TRUE(m.latticeFrame(fig.child).matrix().isApprox((Eigen::Translation3d(0, 0, 0.2) * frame0).matrix(), 1e-14));
  EXPECT_NEAR(m.controlPoints(fig.parent)(4, 2), 1.2, 1e-14);
  // One-way: the child moves alone.
  m.setOneWay(m.bindingsOf(fig.child).front(), true);
  m.applyMotion(fig.child, Eigen::Affine3d(Eigen::Translation3d(0.1, 0, 0)));
  EXPECT_NEAR(m.controlPoints(fig.parent)(4, 0), 0.0, 1e-14);
  EXPECT_NEAR(m.latticeFrame(fig.child).translation().x(), 0.35, 1e-14);
  // Sibling order and removal.
  const WidgetId second = m.addLattice("second", Eigen::Vector3i(2, 2, 2));
  m.bind(fig.topFace, second);
  EXPECT_EQ(m.pipelineOrder(), (std::vector<WidgetId>{fig.parent, fig.child, second}));
  m.setSiblingPosition(second, 0);
  EXPECT_EQ(m.pipelineOrder(), (std::vector<WidgetId>{fig.parent, second, fig.child}));
  const Eigen::Affine3d childWorld = m.latticeFrame(fig.child);
  m.remove(fig.topFace);
  EXPECT_EQ(m.roots().size(), 3u);
  EXPECT_TRUE(m.latticeFrame(fig.child).matrix().isApprox(childWorld.matrix(), 1e-14));
  EXPECT_FALSE(m.attachedCell(fig.faceLift).has_value());  // a free widget now
  m.remove(fig.parent);
  EXPECT_FALSE(m.contains(fig.pointA));
  EXPECT_EQ(m.widgets(WidgetType::Lattice).size(), 3u - 1u);
}

TEST(WidgetModel, RayDragMovesTheCellByExactlyTheRayOffset) {
  WidgetModel m;
  const WidgetId lat = m.addLattice("", Eigen::Vector3i(2, 2, 2));
  const WidgetId top = m.addCell(lat, CellSpec::face(0, 0, 1, 2));
  const WidgetId arrow = m.addAffine(top, AffineKind::Translate);  // at (0.5, 0.5, 1) along +x, size 0.2
  const Eigen::Vector3d eye(0.6, -2.0, 3.0);
  auto rayTo = [&](const Eigen::Vector3d& target) { return Ray{eye, target - eye}; };
  const Ray grab = rayTo({0.6, 0.5, 1.0});
  const auto hit = m.pick(grab);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->id, arrow);  // the arrow wins over the face behind it
  EXPECT_FALSE(m.pick(Ray{{5, 5, 5}, {1, 0, 0}}).has_value());

  m.beginDrag(arrow, grab);
  m.dragTo(rayTo({0.6 + 0.137, 0.5, 1.0}));
  m.dragTo(rayTo({0.6 + 0.237, 0.5, 1.0}));
  m.endGesture();
  const Eigen::MatrixX3d p = m.controlPoints(lat);
  for (Eigen::Index i : m.cellIndices(top)) EXPECT_NEAR(p(i, 0) - m.restPoints(lat)(i, 0), 0.237, 1e-14);
  EXPECT_NEAR(m.variation(arrow), 0.237, 1e-14);
}

TEST(WidgetModel, RayDragTurnsARing) {
  WidgetModel m;
  const WidgetId lat = m.addLattice("", Eigen::Vector3i(2, 2, 2));
  const WidgetId top = m.addCell(lat, CellSpec::face(0, 0, 1, 2));
  const WidgetId ring = m.addAffine(top, AffineKind::Rotate);
  m.setGlyph(ring, Glyph{"ring", 0.3, Eigen::Affine3d::Identity()});
  const Eigen::Vector3d eye(0.5, 0.5, 4.0);
  auto rayTo = [&](double angle) {
    return Ray{eye, Eigen::Vector3d(0.5 + 0.3 * std::cos(angle), 0.5 + 0.3 * std::sin(angle), 1.0) - eye};
  };
  ASSERT_EQ(m.pick(rayTo(0.0))->id, ring);
  m.beginDrag(ring, rayTo(0.0));
  for (double a = 0.1; a <= 2.5 * pi; a += 0.1) m.dragTo(rayTo(a));  // past a full turn: unwrapped
  m.dragTo(rayTo(2.5 * pi));
  m.endGesture();
  EXPECT_NEAR(m.variation(ring), 2.5 * pi, 1e-12);
  EXPECT_TRUE(m.controlPoints(lat).row(4).isApprox(Eigen::RowVector3d(1, 0, 1), 1e-12));  // (0,0,1) turned 90 deg
}

TEST(WidgetModel, RootLatticeDragMovesItsFrameNotItsPoints) {
  Fig62 fig = buildFig62();
  WidgetModel& m = fig.model;
  const Eigen::Affine3d motion(Eigen::Translation3d(1, 2, 3) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()));
  m.applyMotion(fig.lattice, motion);
  EXPECT_TRUE(m.latticeFrame(fig.lattice).isApprox(motion, 1e-15));
  EXPECT_EQ(m.controlPoints(fig.lattice), m.restPoints(fig.lattice));
  // Widgets ride along; a translate still moves its cell by world-true distances.
  m.applyVariation(fig.edgeTranslate, 0.5);
  const Eigen::MatrixX3d w = m.worldControlPoints(fig.lattice);
  EXPECT_TRUE(Eigen::Vector3d(w.row(6).transpose()).isApprox(motion * Eigen::Vector3d(0.5, 1.0, 0.0), 1e-14));
}

TEST(WidgetModel, ChangingAMaskKeepsTheWidgetInPlace) {
  Fig62 fig = buildFig62();
  WidgetModel& m = fig.model;
  m.applyVariation(fig.faceRotate, 0.5);
  const WidgetFrame before = m.affineFrame(fig.faceRotate);
  const BindingId attachment = m.bindingsOf(fig.faceRotate).front();
  m.setMask(attachment, AffineMask::t());
  EXPECT_TRUE(m.affineFrame(fig.faceRotate).frame.isApprox(before.frame, 1e-14));
  EXPECT_EQ(m.binding(attachment).mask, AffineMask::t());
  // Now the ring no longer turns with its face: turning it again keeps its axes... and its
  // frame's x stays where the placement put it.
  m.applyVariation(fig.faceRotate, 0.25);
  EXPECT_TRUE(m.affineFrame(fig.faceRotate).frame.linear().isApprox(before.frame.linear(), 1e-14));
}

// A translate widget turned into a rotate widget: the points stay, the variation restarts,
// the default arrow becomes a ring, and the next drag turns the cell about the widget's z.
TEST(WidgetModel, ChangingTheKindKeepsThePointsAndTurnsTheNextGesture) {
  Fig62 fig = buildFig62();
  WidgetModel& m = fig.model;
  m.applyVariation(fig.edgeTranslate, 0.5);
  const Eigen::MatrixX3d moved = m.controlPoints(fig.lattice);
  m.setAffineKind(fig.edgeTranslate, AffineKind::Rotate);
  EXPECT_EQ(m.affineKind(fig.edgeTranslate), AffineKind::Rotate);
  EXPECT_EQ(m.variation(fig.edgeTranslate), 0.0);
  EXPECT_EQ(m.glyph(fig.edgeTranslate).shape, "ring");
  EXPECT_EQ(m.controlPoints(fig.lattice), moved);

  const WidgetId cell = *m.attachedCell(fig.edgeTranslate);
  const WidgetFrame f = m.affineFrame(fig.edgeTranslate);
  const Eigen::MatrixX3d before = m.cellWorldPoints(cell);
  m.applyVariation(fig.edgeTranslate, pi / 2);
  const Eigen::MatrixX3d after = m.cellWorldPoints(cell);
  const Eigen::Affine3d turn = Eigen::Translation3d(f.frame.translation()) *
                               Eigen::AngleAxisd(pi / 2, f.frame.linear().col(2)) *
                               Eigen::Translation3d(-f.frame.translation());
  for (Eigen::Index i = 0; i < before.rows(); ++i)
    EXPECT_TRUE(Eigen::Vector3d(after.row(i).transpose()).isApprox(turn * Eigen::Vector3d(before.row(i).transpose()), 1e-12));

  // A library part survives a kind change; the data round trip keeps the new kind.
  m.setGlyph(fig.edgeTranslate, Glyph{"crank", 0.3, Eigen::Affine3d::Identity()});
  m.setAffineKind(fig.edgeTranslate, AffineKind::Scale);
  EXPECT_EQ(m.glyph(fig.edgeTranslate).shape, "crank");
  EXPECT_EQ(WidgetModel::fromData(m.toData()).affineKind(fig.edgeTranslate), AffineKind::Scale);
}

// placementBase * placement is the widget's full frame: moving the widget by a world motion M
// through its placement (what the transformer manipulator does) moves its rigid frame by M, on
// a stretched lattice too.
TEST(WidgetModel, PlacementBaseTurnsAWorldMotionIntoAPlacement) {
  Fig62 fig = buildFig62();
  WidgetModel& m = fig.model;
  m.applyMotion(fig.lattice, Eigen::Affine3d(Eigen::Scaling(Eigen::Vector3d(2.0, 0.5, 1.5))));
  m.applyVariation(fig.faceRotate, 0.3);
  const WidgetFrame before = m.affineFrame(fig.faceRotate);
  const Eigen::Affine3d motion(Eigen::Translation3d(0.1, -0.2, 0.3) * Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  const Eigen::Affine3d base = m.placementBase(fig.faceRotate);
  m.setPlacement(fig.faceRotate, base.inverse() * motion * base * m.placement(fig.faceRotate));
  const WidgetFrame after = m.affineFrame(fig.faceRotate);
  EXPECT_TRUE(after.frame.matrix().isApprox((motion * before.frame).matrix(), 1e-12));
  EXPECT_NEAR(after.size, before.size, 1e-12);
  const WidgetId free = m.addFreeAffine(AffineKind::Translate);
  EXPECT_TRUE(m.placementBase(free).matrix().isIdentity(0.0));
}

TEST(WidgetModel, RayDragsCellsInTheViewPlaneAndScalesRadially) {
  WidgetModel m;
  const WidgetId lat = m.addLattice("box", Eigen::Vector3i(2, 2, 2));
  const WidgetId corner = m.addCell(lat, CellSpec::point(1, 1, 1), "corner");
  const Ray grab{{1.0, 1.0, 5.0}, {0, 0, -1}};
  ASSERT_EQ(m.pick(grab)->id, corner);
  m.beginDrag(corner, grab);
  m.dragTo(Ray{{1.2, 0.9, 5.0}, {0, 0, -1}});
  m.endGesture();
  EXPECT_TRUE(m.controlPoints(lat).row(7).isApprox(Eigen::RowVector3d(1.2, 0.9, 1.0), 1e-14));

  const WidgetId bottom = m.addCell(lat, CellSpec::face(0, 0, 0, 2), "bottom");
  const WidgetId scale = m.addAffine(bottom, AffineKind::Scale, "grow");  // at (0.5, 0.5, 0)
  // Parallel (orthographic) rays: the view plane through the widget is z = 0.
  m.beginDrag(scale, Ray{{0.6, 0.5, -3.0}, {0, 0, 1}});
  m.dragTo(Ray{{0.7, 0.5, -3.0}, {0, 0, 1}});
  m.endGesture();
  EXPECT_NEAR(m.variation(scale), std::log(2.0), 1e-14);
  EXPECT_TRUE(m.controlPoints(lat).row(0).isApprox(Eigen::RowVector3d(-0.5, -0.5, 0.0), 1e-14));
}

TEST(WidgetModel, SnapshotRestoreAndCopy) {
  Fig68 fig = buildFig68();
  WidgetModel& m = fig.model;
  const WidgetModelState rest = m.captureState();
  const WidgetModel copy = m;
  m.applyVariation(fig.faceRotateA, 0.4);
  const WidgetModelState turned = m.captureState();
  m.restoreState(rest);
  EXPECT_EQ(m.controlPoints(fig.lattice), copy.controlPoints(fig.lattice));
  EXPECT_EQ(m.variation(fig.faceRotateB), 0.0);
  m.restoreState(turned);
  EXPECT_EQ(m.variation(fig.faceRotateB), 0.4);
  EXPECT_EQ(copy.variation(fig.faceRotateB), 0.0);  // copies are independent
}

TEST(WidgetModel, DataRoundTripRebuildsTheSameModel) {
  for (WidgetModel m : {buildFig62().model, buildFig68().model, buildFig69().model, buildFig610(0.1, VariationRange{0, 1}).model}) {
    const WidgetModelData d = m.toData();
    const WidgetModel back = WidgetModel::fromData(d);
    const WidgetModelData d2 = back.toData();
    EXPECT_EQ(d2.bindings, d.bindings);
    EXPECT_EQ(d2.rootOrder, d.rootOrder);
    for (WidgetId l : m.widgets(WidgetType::Lattice))
      EXPECT_EQ(back.worldControlPoints(l), m.worldControlPoints(l));
    for (WidgetId a : m.widgets(WidgetType::Affine))
      EXPECT_TRUE(back.affineFrame(a).frame.isApprox(m.affineFrame(a).frame, 0.0));
  }
  WidgetModelData bad = buildFig62().model.toData();
  bad.cells[1].lattice = WidgetId{42};
  auto e = expectError(WidgetErrorCode::UnknownWidget, [&] { WidgetModel::fromData(bad); });
  EXPECT_EQ(e.where(), "/cells/1/lattice");
}

// A network whose every gesture is exactly invertible: disjoint cells, translate widgets,
// rotate widgets on faces (T, R follow), scale widgets at their box's centre, cell bindings of
// translations, and a free handle.
struct Network {
  WidgetModel m;
  WidgetId lattice;
  std::vector<WidgetId> drivers;
  WidgetId cellF;
};

Network buildNetwork() {
  Network n;
  WidgetModel& m = n.m;
  n.lattice = m.addLattice("", Eigen::Vector3i(4, 4, 4));
  const WidgetId faceA = m.addCell(n.lattice, CellSpec::face(0, 0, 0, 2));
  const WidgetId faceB = m.addCell(n.lattice, CellSpec::face(2, 2, 3, 2));
  const WidgetId edgeC = m.addCell(n.lattice, CellSpec::edge(0, 3, 3, 0));
  const WidgetId pointE = m.addCell(n.lattice, CellSpec::point(2, 0, 2));
  n.cellF = m.addCell(n.lattice, CellSpec::point(0, 2, 1));
  const WidgetId boxG = m.addCell(n.lattice, CellSpec::box(1, 2, 1));
  const Eigen::Affine3d tilted = pointing(Eigen::Vector3d(1, 2, 3).normalized(), Eigen::Vector3d(0.1, -0.2, 0.05));
  const WidgetId ta = m.addAffine(faceA, AffineKind::Translate, "", tilted);
  const WidgetId rb = m.addAffine(faceB, AffineKind::Rotate, "", tilted);
  const WidgetId tc = m.addAffine(edgeC, AffineKind::Translate, "", pointing({0, 1, 1}));
  const WidgetId te = m.addAffine(pointE, AffineKind::Translate, "", pointing({-1, 0, 1}));
  const WidgetId sg = m.addAffine(boxG, AffineKind::Scale);
  const WidgetId h = m.addFreeAffine(AffineKind::Rotate);
  m.bind(ta, tc, ConversionRule(-0.5));
  m.bind(ta, te, ConversionRule(2.0));
  m.bind(rb, sg, ConversionRule(0.3));
  m.bind(h, rb);
  m.bind(n.cellF, pointE, AffineMask::t());
  n.drivers = {ta, rb, tc, te, sg, h};
  return n;
}

struct Gesture {
  std::size_t driver;  // index into drivers, or drivers.size() for the cell F
  double delta;
  Eigen::Vector3d move;
};

std::vector<Gesture> randomGestures(std::size_t count, unsigned seed, std::size_t drivers) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, drivers);
  std::uniform_real_distribution<double> amount(-0.3, 0.3);
  std::vector<Gesture> out;
  for (std::size_t i = 0; i < count; ++i) out.push_back({pick(rng), amount(rng), {amount(rng), amount(rng), amount(rng)}});
  return out;
}

void play(Network& n, const Gesture& g, double sign) {
  if (g.driver < n.drivers.size()) {
    n.m.applyVariation(n.drivers[g.driver], sign * g.delta);
  } else {
    n.m.applyMotion(n.cellF, Eigen::Affine3d(Eigen::Translation3d(sign * g.move)));
  }
}

TEST(WidgetModel, ThousandGesturesAndTheirInversesReturnToRest) {
  Network n = buildNetwork();
  const std::vector<Gesture> gestures = randomGestures(1000, 2026, n.drivers.size());
  for (const Gesture& g : gestures) play(n, g, 1.0);
  const Eigen::MatrixX3d forward = n.m.controlPoints(n.lattice);
  EXPECT_GT((forward - n.m.restPoints(n.lattice)).cwiseAbs().maxCoeff(), 0.1);
  for (auto it = gestures.rbegin(); it != gestures.rend(); ++it) play(n, *it, -1.0);
  EXPECT_LE((n.m.controlPoints(n.lattice) - n.m.restPoints(n.lattice)).cwiseAbs().maxCoeff(), 1e-9);
  for (WidgetId a : n.drivers) EXPECT_NEAR(n.m.variation(a), 0.0, 1e-9);

  // The same sequence on a fresh model gives bit-identical results.
  Network again = buildNetwork();
  for (const Gesture& g : gestures) play(again, g, 1.0);
  EXPECT_EQ(again.m.controlPoints(again.lattice), forward);
}

TEST(WidgetModel, RenameMovesTheNameAndOnlyChangesOnANewName) {
  WidgetModel m;
  const WidgetId box = m.addLattice("box", Eigen::Vector3i(2, 2, 2));
  const std::uint64_t before = m.revision();
  m.rename(box, "box");  // the same name: nothing to do
  EXPECT_EQ(m.revision(), before);
  m.rename(box, "crate");
  EXPECT_GT(m.revision(), before);
  EXPECT_EQ(m.name(box), "crate");
  EXPECT_EQ(m.find("crate"), box);
  EXPECT_THROW(m.find("box"), WidgetError);
  // The old name is free again, the new one taken.
  const WidgetId other = m.addLattice("box", Eigen::Vector3i(2, 2, 2));
  EXPECT_EQ(m.find("box"), other);
  EXPECT_THROW(m.rename(other, "crate"), WidgetError);
}

TEST(WidgetModel, AffineFramesStayRigidInANonUniformlyScaledLattice) {
  // A widget's world frame is the rigid part of L * mask(A_cell) * C0 * O (Kuriyama 1996, sec. 6.2.1): with a lattice
  // frame scaled (1, 2, 3) it must still be a rotation, located at the cell's world centroid.
  WidgetModel m;
  LatticeOptions o;
  o.counts = Eigen::Vector3i(2, 2, 2);
  o.frame = Eigen::Translation3d(1, 2, 3) * Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()) * Eigen::Scaling(1.0, 2.0, 3.0);
  const WidgetId l = m.addLattice(o);
  const WidgetId face = m.addCell(l, CellSpec::face(0, 0, 1, 2));
  const WidgetId ring = m.addAffine(face, AffineKind::Rotate, "ring");
  const WidgetFrame f = m.affineFrame(ring);
  const Eigen::Matrix3d r = f.frame.linear();
  EXPECT_LT((r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
  EXPECT_LT((f.frame.translation() - o.frame * Eigen::Vector3d(0.5, 0.5, 1.0)).norm(), 1e-12);
  // Its z is the face's world normal: the lattice z axis turned into the world.
  EXPECT_LT((r.col(2) - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
}

TEST(WidgetModel, UnknownAndRemovedBindingsAreRefused) {
  WidgetModel m;
  const WidgetId box = m.addLattice("box", Eigen::Vector3i(2, 2, 2));
  const WidgetId a = m.addAffine(m.addCell(box, CellSpec::point(0, 0, 0)), AffineKind::Translate, "a");
  const WidgetId b = m.addAffine(m.addCell(box, CellSpec::point(1, 0, 0)), AffineKind::Translate, "b");
  const BindingId bound = m.bind(a, b, ConversionRule(2.0));
  EXPECT_EQ(m.binding(bound).rule.gain, 2.0);
  expectError(WidgetErrorCode::UnknownWidget, [&] { m.binding(BindingId{999}); });
  expectError(WidgetErrorCode::UnknownWidget, [&] { m.binding(BindingId{}); });
  m.unbind(bound);
  expectError(WidgetErrorCode::UnknownWidget, [&] { m.binding(bound); });
  expectError(WidgetErrorCode::UnknownWidget, [&] { m.setRule(bound, ConversionRule(3.0)); });
}

}  // namespace
}  // namespace ffdkit::widgets
