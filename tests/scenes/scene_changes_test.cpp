// Scene revisions and change sets (scene_changes.h), and the deformer consuming them: each edit
// reports exactly what it changed; a drag step builds no lattice and embeds nothing (and a
// gesture step updates by deltas, made exact by the next exact update); a look
// or a camera edit leaves the deformed points (and their revision) alone.
#include "ffdkit/scenes/scene_changes.h"

#include <functional>
#include <set>

#include <gtest/gtest.h>

#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/lattice_fit.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "scenes_test_support.h"

namespace ffdkit::scenes {
namespace {
using test_support::sphereObject;

TEST(SceneChanges, EachEditReportsWhatItChanged) {
  Scene scene;
  SceneMark mark = markOf(scene);
  scene.addObject(sphereObject("a"));
  SceneChanges c = changesSince(scene, mark);
  EXPECT_TRUE(c.structure);
  EXPECT_EQ(c.meshes, std::vector<ObjectId>{scene.objectId("a")});
  EXPECT_EQ(c.looks, std::vector<ObjectId>{scene.objectId("a")});
  EXPECT_FALSE(c.camera);
  EXPECT_TRUE(c.widgets.empty());
  scene.addObject(sphereObject("b"));

  mark = markOf(scene);
  DisplaySettings look;
  look.color = {0.1, 0.2, 0.3};
  scene.setObjectDisplay("b", look);
  c = changesSince(scene, mark);
  EXPECT_EQ(c.looks, std::vector<ObjectId>{scene.objectId("b")});
  EXPECT_TRUE(c.meshes.empty());
  EXPECT_FALSE(c.structure);
  EXPECT_FALSE(c.camera);

  mark = markOf(scene);
  Camera camera;
  camera.position = {5, 5, 5};
  scene.setCamera(camera);
  c = changesSince(scene, mark);
  EXPECT_TRUE(c.camera);
  EXPECT_TRUE(c.looks.empty() && c.meshes.empty() && !c.structure && c.widgets.empty());

  mark = markOf(scene);
  scene.setObjectMesh("a", sphereObject("a", 8).mesh);
  c = changesSince(scene, mark);
  EXPECT_EQ(c.meshes, std::vector<ObjectId>{scene.objectId("a")});
  EXPECT_TRUE(c.looks.empty() && !c.structure && !c.camera);

  mark = markOf(scene);
  const widgets::WidgetId lattice = attachNewLattice(scene, {"a", "b"});
  c = changesSince(scene, mark);
  EXPECT_TRUE(c.structure);
  EXPECT_TRUE(c.widgets.structure);
  EXPECT_EQ(c.widgets.frames, std::vector<widgets::WidgetId>{lattice});
  EXPECT_TRUE(c.meshes.empty() && c.looks.empty());

  mark = markOf(scene);
  scene.widgets.setControlPoints(lattice, scene.widgets.controlPoints(lattice) * 1.1);
  c = changesSince(scene, mark);
  EXPECT_EQ(c.widgets.controlPoints, std::vector<widgets::WidgetId>{lattice});
  EXPECT_TRUE(c.widgets.frames.empty() && !c.structure && c.meshes.empty());

  mark = markOf(scene);
  scene.detach(lattice, "b");
  EXPECT_TRUE(changesSince(scene, mark).structure);
  mark = markOf(scene);
  scene.removeObject("a");  // the attachment loses its last object and goes
  c = changesSince(scene, mark);
  EXPECT_TRUE(c.structure);
  EXPECT_TRUE(scene.attachments().empty());

  mark = markOf(scene);
  scene.widgets = widgets::WidgetModel();  // replaced: its revisions are another history
  EXPECT_TRUE(changesSince(scene, mark).widgetsReplaced);
  EXPECT_TRUE(changesSince(scene, markOf(scene)).empty());
}

// Which of a scene's stamps an edit moved: "structure", "camera", "animation", "widgets", and
// "mesh:<name>" / "look:<name>" per object. A stamp moved when it is newer than the scene's
// revision before the edit (the widget model counts its own revisions).
std::set<std::string> stampsMovedBy(Scene& scene, const std::function<void()>& edit) {
  const std::uint64_t before = scene.revision();
  const std::uint64_t widgetsBefore = scene.widgets.revision();
  edit();
  std::set<std::string> moved;
  if (scene.structureRevision() > before) moved.insert("structure");
  if (scene.cameraRevision() > before) moved.insert("camera");
  if (scene.animationRevision() > before) moved.insert("animation");
  if (scene.widgets.revision() != widgetsBefore) moved.insert("widgets");
  for (const SceneObject& o : scene.objects()) {
    if (o.meshRevision > before) moved.insert("mesh:" + o.name);
    if (o.displayRevision > before) moved.insert("look:" + o.name);
  }
  // The scene's own revision moves exactly when one of its stamps did.
  EXPECT_EQ(scene.revision() > before, !moved.empty() && moved != std::set<std::string>{"widgets"});
  return moved;
}

using Stamps = std::set<std::string>;

TEST(SceneRevisions, EachEditBumpsExactlyTheRevisionsItShould) {
  Scene scene;
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.addObject(sphereObject("a")); }), (Stamps{"structure", "mesh:a", "look:a"}));
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.addObject(sphereObject("b")); }), (Stamps{"structure", "mesh:b", "look:b"}));
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.setObjectMesh("a", sphereObject("a", 6).mesh); }), Stamps{"mesh:a"});
  const PrimitiveOptions cube{.kind = PrimitiveKind::Cube};
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.setObjectMesh("b", buildObjectMesh(cube, "."), cube); }), Stamps{"mesh:b"});
  EXPECT_EQ(std::get<PrimitiveOptions>(scene.findObject("b")->source).kind, PrimitiveKind::Cube);
  SceneObject taken;
  EXPECT_EQ(stampsMovedBy(scene, [&] { taken = scene.takeObject("b"); }), Stamps{"structure"});
  EXPECT_EQ(taken.name, "b");
  EXPECT_EQ(scene.findObject("b"), nullptr);
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.insertObject(0, std::move(taken)); }), (Stamps{"structure", "mesh:b", "look:b"}));
  EXPECT_EQ(scene.objects().front().name, "b");
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.setObjectDisplay("b", DisplaySettings{.opacity = 0.5}); }), Stamps{"look:b"});
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.setCamera(Camera{.viewAngleDegrees = 40.0}); }), Stamps{"camera"});
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.setBackground({1.0, 1.0, 1.0}); }), Stamps{"camera"});

  widgets::WidgetId lattice;
  EXPECT_EQ(stampsMovedBy(scene, [&] { lattice = attachNewLattice(scene, {"a"}); }), (Stamps{"structure", "widgets"}));
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.attach(lattice, "b"); }), Stamps{"structure"});
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.attach(lattice, "b"); }), Stamps{});  // already attached
  EXPECT_EQ(scene.latticesDeforming("b"), std::vector<widgets::WidgetId>{lattice});
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.detach(lattice, "b"); }), Stamps{"structure"});
  const std::vector<Attachment> attached = scene.attachments();
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.setAttachments(attached); }), Stamps{});  // the same attachments
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.setAttachments({}); }), Stamps{"structure"});
  EXPECT_TRUE(scene.latticesDeforming("a").empty());
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.setAttachments(attached); }), Stamps{"structure"});
  const ObjectId a = scene.objectId("a");
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.renameObject("a", "c"); }), Stamps{"structure"});
  EXPECT_EQ(scene.objectId("c"), a);  // a rename keeps the id
  EXPECT_EQ(scene.attachments().front().objects, std::vector<ObjectId>{a});  // the link holds the id

  Keyframe key;
  key.frame = scene.widgets.latticeFrame(lattice);
  EXPECT_EQ(stampsMovedBy(scene, [&] { setKey(scene, lattice, ChannelKind::LatticeFrame, key); }), Stamps{"animation"});
  EXPECT_EQ(stampsMovedBy(scene, [&] { removeKey(scene, lattice, ChannelKind::LatticeFrame, 0.0); }), Stamps{"animation"});
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.setFrameRate(30.0); }), Stamps{"animation"});
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.setFrameRange(-2, 48); }), Stamps{"animation"});
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.setAnimation(Animation{}); }), Stamps{"animation"});

  // The widget model's edits are its own: the scene's revisions stay.
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.widgets.setLatticeCounts(lattice, {4, 4, 4}); }), Stamps{"widgets"});
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.widgets.remove(lattice); }), Stamps{"widgets"});
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.dropStaleAttachments(); }), Stamps{"structure"});
  EXPECT_TRUE(scene.attachments().empty());
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.dropStaleAttachments(); }), Stamps{});
  EXPECT_EQ(stampsMovedBy(scene, [&] { scene.removeObject("c"); }), Stamps{"structure"});

  // Refused edits change nothing.
  EXPECT_EQ(stampsMovedBy(scene, [&] { EXPECT_THROW(scene.renameObject("b", ""), std::invalid_argument); }), Stamps{});
  scene.addObject(sphereObject("d"));
  EXPECT_EQ(stampsMovedBy(scene, [&] { EXPECT_THROW(scene.renameObject("b", "d"), std::invalid_argument); }), Stamps{});
  EXPECT_EQ(stampsMovedBy(scene, [&] { EXPECT_THROW(scene.detach(lattice, "b"), std::invalid_argument); }), Stamps{});
  EXPECT_EQ(stampsMovedBy(scene, [&] { EXPECT_THROW(scene.setObjectMesh("x", {}), std::invalid_argument); }), Stamps{});
}

TEST(SceneChanges, EditsRefuseUnknownAndDuplicateObjects) {
  Scene scene;
  scene.addObject(sphereObject("a"));
  EXPECT_THROW(scene.addObject(sphereObject("a")), std::invalid_argument);
  EXPECT_THROW(scene.setObjectDisplay("nope", {}), std::invalid_argument);
  EXPECT_THROW(scene.removeObject("nope"), std::invalid_argument);
  EXPECT_THROW(scene.setObjectMesh("nope", {}), std::invalid_argument);
}

TEST(LatticeFit, PadsByTheDiagonalAndGivesFlatBoxesTheMinimumThickness) {
  const Eigen::AlignedBox3d flat(Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(3, 4, 1));  // diagonal 5
  const Eigen::AlignedBox3d padded = fittedLatticeBox(flat, 0.1);
  EXPECT_TRUE(padded.min().isApprox(Eigen::Vector3d(-0.5, -0.5, 0.5), 1e-15));
  EXPECT_TRUE(padded.max().isApprox(Eigen::Vector3d(3.5, 4.5, 1.5), 1e-15));
  const Eigen::AlignedBox3d bare = fittedLatticeBox(flat, 0.0);
  EXPECT_NEAR(bare.sizes().z(), kMinimumLatticeThickness * 5.0, 1e-14);
  EXPECT_DOUBLE_EQ(bare.center().z(), 1.0);
  const Eigen::AlignedBox3d point = fittedLatticeBox(Eigen::AlignedBox3d(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1, 2, 3)), 0.05);
  EXPECT_LE((point.sizes() - Eigen::Vector3d::Constant(kMinimumLatticeThickness)).cwiseAbs().maxCoeff(), 1e-14);
  const Eigen::Affine3d frame = fittedLatticeFrame(flat, 0.1);
  EXPECT_TRUE((frame * Eigen::Vector3d(1, 1, 1)).isApprox(padded.max(), 1e-15));
  EXPECT_THROW(fittedLatticeBox(Eigen::AlignedBox3d(), 0.1), std::invalid_argument);
  EXPECT_THROW(fittedLatticeBox(flat, -1.0), std::invalid_argument);
}

TEST(SceneDeformer, ADragStepWritesControlPointsInPlaceAndBuildsNoLattice) {
  Scene scene;
  scene.addObject(sphereObject("a"));
  scene.addObject(sphereObject("b"));
  AttachOptions options;
  options.counts = {4, 4, 4};
  const widgets::WidgetId lattice = attachNewLattice(scene, {"a"}, options);
  SceneDeformer deformer;
  deformer.update(scene);
  EXPECT_EQ(deformer.lastStats().latticesBuilt, 1);
  EXPECT_EQ(deformer.lastStats().reembeddedStages, 1);
  const std::uint64_t a0 = deformer.revision("a"), b0 = deformer.revision("b");

  for (int step = 1; step <= 3; ++step) {
    Eigen::MatrixX3d p = scene.widgets.controlPoints(lattice);
    p(21, 2) += 0.05;
    scene.widgets.setControlPoints(lattice, p);
    deformer.update(scene, lattice);
    EXPECT_EQ(deformer.lastStats().latticesBuilt, 0);
    EXPECT_EQ(deformer.lastStats().reembeddedStages, 0);
    EXPECT_EQ(deformer.revision("a"), a0 + std::uint64_t(step));
    EXPECT_EQ(deformer.revision("b"), b0);  // not deformed by the lattice
  }
  // The result is the one-shot evaluation's.
  const auto expected = deformScene(scene);
  EXPECT_LE((deformer.points("a") - expected.at("a")).cwiseAbs().maxCoeff(), 1e-12);

  // A look, a camera or nothing at all: no deformation.
  DisplaySettings look;
  look.opacity = 0.5;
  scene.setObjectDisplay("a", look);
  scene.setCamera(Camera{});
  deformer.update(scene);
  EXPECT_EQ(deformer.revision("a"), a0 + 3);
  EXPECT_EQ(deformer.lastStats().latticesBuilt, 0);

  // A new frame moves the lattice in place and re-embeds it; a copy of the model (another
  // instance) is synced in full without building a lattice when nothing differs.
  scene.widgets.setLatticeFrame(lattice, Eigen::Translation3d(0.01, 0, 0) * scene.widgets.latticeFrame(lattice));
  deformer.update(scene);
  EXPECT_EQ(deformer.lastStats().latticesBuilt, 0);
  EXPECT_EQ(deformer.lastStats().reembeddedStages, 1);
  scene.widgets = widgets::WidgetModel(scene.widgets);
  deformer.update(scene);
  EXPECT_EQ(deformer.lastStats().latticesBuilt, 0);
  EXPECT_EQ(deformer.lastStats().reembeddedStages, 0);
  EXPECT_EQ(deformer.revision("a"), a0 + 4);

  // A new mesh is noticed through its revision.
  scene.setObjectMesh("a", sphereObject("a", 6).mesh);
  deformer.update(scene);
  EXPECT_EQ(deformer.points("a").rows(), scene.findObject("a")->mesh.points.rows());
  EXPECT_EQ(deformer.lastStats().latticesBuilt, 1);
}

TEST(SceneDeformer, GestureStepsUpdateByDeltasAndAnExactUpdateRestoresTheExactResult) {
  Scene scene;
  scene.addObject(sphereObject("a", 24));
  AttachOptions options;
  options.counts = {4, 4, 4};
  const widgets::WidgetId lattice = attachNewLattice(scene, {"a"}, options);
  SceneDeformer deformer;
  deformer.update(scene);
  for (int step = 1; step <= 5; ++step) {
    Eigen::MatrixX3d p = scene.widgets.controlPoints(lattice);
    p(21, 2) += 0.05;
    p(42, 0) -= 0.03;
    scene.widgets.setControlPoints(lattice, p);
    deformer.updateGesture(scene, lattice);
    EXPECT_EQ(deformer.lastStats().deltaStages, 1);
    EXPECT_EQ(deformer.lastStats().latticesBuilt, 0);
    EXPECT_EQ(deformer.lastStats().reembeddedStages, 0);
    EXPECT_LE((deformer.points("a") - deformScene(scene).at("a")).cwiseAbs().maxCoeff(), 1e-13);
  }
  // Nothing moved since: an exact update still evaluates the lattice in full, bit for bit.
  const std::uint64_t revision = deformer.revision("a");
  deformer.update(scene);
  EXPECT_EQ(deformer.lastStats().deltaStages, 0);
  EXPECT_EQ(deformer.revision("a"), revision + 1);
  EXPECT_TRUE(deformer.points("a") == deformScene(scene).at("a"));
  deformer.finishGesture(scene);
  EXPECT_EQ(deformer.revision("a"), revision + 1);  // nothing left to do
}

}  // namespace
}  // namespace ffdkit::scenes
