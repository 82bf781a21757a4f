#include "ffdkit/scenes/scene_deformer.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "ffdkit/scenes/scene_file.h"

namespace ffdkit::scenes {
namespace {

const std::filesystem::path kExamples = FFDKIT_SOURCE_DIR "/scenes/examples";

AttachOptions withCounts(int l, int m, int n) {
  AttachOptions options;
  options.counts = {l, m, n};
  return options;
}

Scene sphereScene() {
  Scene scene;
  SceneObject sphere;
  sphere.name = "sphere";
  sphere.source = PrimitiveOptions{.kind = PrimitiveKind::Sphere, .resolution = 16};
  sphere.mesh = buildObjectMesh(sphere.source, ".");
  scene.objects.push_back(sphere);
  return scene;
}

TEST(SceneDeformer, AnObjectWithNoLatticeKeepsItsPoints) {
  const Scene scene = sphereScene();
  SceneDeformer deformer;
  deformer.update(scene);
  EXPECT_EQ(deformer.points("sphere"), scene.objects[0].mesh.points);
}

TEST(SceneDeformer, AttachedLatticeAtRestReproducesThePoints) {
  Scene scene = sphereScene();
  attachNewLattice(scene, {"sphere"}, withCounts(4, 3, 5));
  SceneDeformer deformer;
  deformer.update(scene);
  EXPECT_LE((deformer.points("sphere") - scene.objects[0].mesh.points).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(SceneDeformer, MovingEveryControlPointAffinelyMovesTheObjectAffinely) {
  Scene scene = sphereScene();
  const auto lattice = attachNewLattice(scene, {"sphere"}, withCounts(3, 3, 3));
  SceneDeformer deformer;
  deformer.update(scene);
  // An affine map of the lattice's local space, applied to every control point.
  Eigen::Affine3d local = Eigen::Translation3d(0.1, -0.2, 0.3) * Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()) *
                          Eigen::Scaling(1.2, 0.9, 1.1);
  Eigen::MatrixX3d points = scene.widgets.controlPoints(lattice);
  for (Eigen::Index i = 0; i < points.rows(); ++i) points.row(i) = (local * Eigen::Vector3d(points.row(i))).transpose();
  scene.widgets.setControlPoints(lattice, points);
  deformer.update(scene);  // an edit: incremental
  const Eigen::Affine3d frame = scene.widgets.latticeFrame(lattice);
  const Eigen::Affine3d world = frame * local * frame.inverse();
  const Eigen::MatrixX3d& deformed = deformer.points("sphere");
  for (Eigen::Index i = 0; i < deformed.rows(); ++i) {
    const Eigen::Vector3d expected = world * Eigen::Vector3d(scene.objects[0].mesh.points.row(i));
    EXPECT_LE((Eigen::Vector3d(deformed.row(i)) - expected).norm(), 1e-12) << "point " << i;
  }
  EXPECT_EQ(deformer.lastStats().reembeddedStages, 0) << "an edit of control points must not re-embed";
}

TEST(SceneDeformer, DetachRestoresTheObjectsOwnPoints) {
  Scene scene = sphereScene();
  AttachOptions named;
  named.latticeName = "box";
  const auto lattice = attachNewLattice(scene, {"sphere"}, named);
  Eigen::MatrixX3d points = scene.widgets.controlPoints(lattice);
  points.col(2) *= 2.0;
  scene.widgets.setControlPoints(lattice, points);
  SceneDeformer deformer;
  deformer.update(scene);
  EXPECT_GT((deformer.points("sphere") - scene.objects[0].mesh.points).cwiseAbs().maxCoeff(), 0.1);
  detachLattice(scene, "box", "sphere");
  deformer.update(scene);
  EXPECT_EQ(deformer.points("sphere"), scene.objects[0].mesh.points);
  EXPECT_THROW(detachLattice(scene, "box", "sphere"), std::invalid_argument);
}

TEST(SceneDeformer, HierarchyRunsParentThenChild) {
  // Fig. 6-9 sample: the parent's top face lifted by 0.2 stretches z by 1.2; the child (at rest)
  // adds nothing. Every point of the column must follow the parent's map.
  const Scene scene = readScene(kExamples / "hierarchy");
  const auto deformed = deformScene(scene);
  const SceneObject& column = scene.objects.at(0);
  const Eigen::MatrixX3d& out = deformed.at(column.name);
  const auto parent = scene.widgets.find("parent");
  const ffd::Lattice lattice = scene.widgets.ffdLattice(parent);
  for (Eigen::Index i = 0; i < out.rows(); ++i) {
    const Eigen::Vector3d q = column.mesh.points.row(i);
    const Eigen::Vector3d local = lattice.frame().inverse() * q;
    if ((local.array() < 0.0).any() || (local.array() > 1.0).any()) continue;  // outside: Identity
    const Eigen::Vector3d expected = lattice.frame() * lattice.evaluate(local);
    EXPECT_LE((Eigen::Vector3d(out.row(i)) - expected).norm(), 1e-9) << "point " << i << " at " << q.transpose();
  }
}

TEST(SceneDeformer, CylindricalLatticeEmbedsTheWholeCylinderIncludingItsAxis) {
  // EFFD (Fig. 6-11): the cylinder lies inside its cylindrical lattice, caps and axis included.
  const Scene scene = readScene(kExamples / "cylinder-twist");
  SceneDeformer deformer;
  deformer.update(scene);
  EXPECT_EQ(deformer.lastStats().outsidePoints, 0);
  EXPECT_EQ(deformer.lastStats().failedPoints, 0);
  // The top cap is turned by the twist: its rim points moved, its centre stays on the axis.
  const SceneObject& cylinder = scene.objects.at(0);
  const Eigen::MatrixX3d& out = deformer.points(cylinder.name);
  for (Eigen::Index i = 0; i < out.rows(); ++i) {
    const Eigen::Vector3d q = cylinder.mesh.points.row(i);
    if (q.head<2>().norm() < 1e-12) {
      EXPECT_LE(Eigen::Vector2d(out(i, 0), out(i, 1)).norm(), 1e-9) << "axis point " << i;
    }
  }
}

TEST(SceneDeformer, EverySampleSceneDeformsToFinitePoints) {
  for (const char* name : {"default", "press", "vise", "mirror", "hierarchy", "cylinder-twist"}) {
    SCOPED_TRACE(name);
    const Scene scene = readScene(kExamples / name);
    SceneDeformer deformer;
    deformer.update(scene);
    deformer.finishGesture(scene);
    EXPECT_EQ(deformer.lastStats().failedPoints, 0);
    for (const auto& object : scene.objects) {
      const Eigen::MatrixX3d& points = deformer.points(object.name);
      EXPECT_TRUE(points.allFinite());
      EXPECT_GT((points - object.mesh.points).cwiseAbs().maxCoeff(), 1e-3) << "the sample should show a deformation";
    }
  }
}

}  // namespace
}  // namespace ffdkit::scenes
