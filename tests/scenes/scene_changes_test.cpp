// Scene revisions and change sets (scene_changes.h), and the deformer consuming them: each edit
// reports exactly what it changed; a drag step builds no lattice and embeds nothing (and a
// gesture step updates by deltas, made exact by the next exact update); a look
// or a camera edit leaves the deformed points (and their revision) alone.
#include "ffdkit/scenes/scene_changes.h"

#include <gtest/gtest.h>

#include "ffdkit/scenes/lattice_fit.h"
#include "ffdkit/scenes/scene_deformer.h"

namespace ffdkit::scenes {
namespace {

SceneObject sphere(const std::string& name, int resolution = 12) {
  SceneObject object;
  object.name = name;
  object.source = PrimitiveOptions{.kind = PrimitiveKind::Sphere, .resolution = resolution};
  object.mesh = buildObjectMesh(object.source, ".");
  return object;
}

TEST(SceneChanges, EachEditReportsWhatItChanged) {
  Scene scene;
  SceneMark mark = markOf(scene);
  addObject(scene, sphere("a"));
  SceneChanges c = changesSince(scene, mark);
  EXPECT_TRUE(c.structure);
  EXPECT_EQ(c.meshes, std::vector<std::string>{"a"});
  EXPECT_EQ(c.looks, std::vector<std::string>{"a"});
  EXPECT_FALSE(c.camera);
  EXPECT_TRUE(c.widgets.empty());
  addObject(scene, sphere("b"));

  mark = markOf(scene);
  DisplaySettings look;
  look.color = {0.1, 0.2, 0.3};
  setObjectDisplay(scene, "b", look);
  c = changesSince(scene, mark);
  EXPECT_EQ(c.looks, std::vector<std::string>{"b"});
  EXPECT_TRUE(c.meshes.empty());
  EXPECT_FALSE(c.structure);
  EXPECT_FALSE(c.camera);

  mark = markOf(scene);
  Camera camera;
  camera.position = {5, 5, 5};
  setCamera(scene, camera);
  c = changesSince(scene, mark);
  EXPECT_TRUE(c.camera);
  EXPECT_TRUE(c.looks.empty() && c.meshes.empty() && !c.structure && c.widgets.empty());

  mark = markOf(scene);
  setObjectMesh(scene, "a", sphere("a", 8).mesh);
  c = changesSince(scene, mark);
  EXPECT_EQ(c.meshes, std::vector<std::string>{"a"});
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
  detachLattice(scene, lattice, "b");
  EXPECT_TRUE(changesSince(scene, mark).structure);
  mark = markOf(scene);
  removeObject(scene, "a");  // the attachment loses its last object and goes
  c = changesSince(scene, mark);
  EXPECT_TRUE(c.structure);
  EXPECT_TRUE(scene.attachments.empty());

  mark = markOf(scene);
  scene.widgets = widgets::WidgetModel();  // replaced: its revisions are another history
  EXPECT_TRUE(changesSince(scene, mark).widgetsReplaced);
  EXPECT_TRUE(changesSince(scene, markOf(scene)).empty());
}

TEST(SceneChanges, EditsRefuseUnknownAndDuplicateObjects) {
  Scene scene;
  addObject(scene, sphere("a"));
  EXPECT_THROW(addObject(scene, sphere("a")), std::invalid_argument);
  EXPECT_THROW(setObjectDisplay(scene, "nope", {}), std::invalid_argument);
  EXPECT_THROW(removeObject(scene, "nope"), std::invalid_argument);
  EXPECT_THROW(touchMesh(scene, "nope"), std::invalid_argument);
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
  addObject(scene, sphere("a"));
  addObject(scene, sphere("b"));
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
  setObjectDisplay(scene, "a", look);
  setCamera(scene, Camera{});
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
  setObjectMesh(scene, "a", sphere("a", 6).mesh);
  deformer.update(scene);
  EXPECT_EQ(deformer.points("a").rows(), scene.findObject("a")->mesh.points.rows());
  EXPECT_EQ(deformer.lastStats().latticesBuilt, 1);
}

TEST(SceneDeformer, GestureStepsUpdateByDeltasAndAnExactUpdateRestoresTheExactResult) {
  Scene scene;
  addObject(scene, sphere("a", 24));
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
