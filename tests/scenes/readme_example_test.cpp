// The scripting examples of README.md, verbatim in spirit: if this test changes, update the README.
#include <numbers>

#include <gtest/gtest.h>

#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/scene_file.h"
#include "ffdkit/widgets/widget_model.h"

namespace ffdkit {
namespace {

TEST(ReadmeExample, TurningABoundKnobTurnsTheTopAndPushesTheSide) {
  using namespace widgets;
  WidgetModel model;
  const WidgetId box = model.addLattice("box", Eigen::Vector3i(3, 3, 3));
  const WidgetId top = model.addCell(box, CellSpec::slab(2, 2), "top");
  const WidgetId knob = model.addAffine(top, AffineKind::Rotate, "knob");
  const WidgetId side = model.addCell(box, CellSpec::face(0, 0, 0, 0), "side");
  const WidgetId push = model.addAffine(side, AffineKind::Translate, "push");
  model.bind(knob, push, ConversionRule(0.1));
  model.applyVariation(model.find("knob"), std::numbers::pi / 2);
  const Eigen::MatrixX3d& p = model.controlPoints(box);
  ASSERT_EQ(p.rows(), 27);
  // The top slab turned 90 degrees about its centre (0.5, 0.5, 1): the corner (0,0,1) -> (1,0,1).
  EXPECT_LE((p.row(18) - Eigen::RowVector3d(1, 0, 1)).norm(), 1e-12);
  EXPECT_NEAR(model.variation(push), 0.1 * std::numbers::pi / 2, 1e-15);
}

TEST(ReadmeExample, OneTurnOfThePressHandleLowersTheBlockTopToTheClamp) {
  scenes::Scene scene = scenes::readScene(std::filesystem::path(FFDKIT_SOURCE_DIR "/scenes/examples/press"));
  scene.widgets.setVariation(scene.widgets.find("handle"), 2 * std::numbers::pi);
  scenes::SceneDeformer deformer;
  deformer.update(scene);
  const Eigen::MatrixX3d& points = deformer.points("block");
  // Pitch 0.4 per turn, clamped at 0.3: the 2x2x2 lattice's top face at z = 1 moves to 0.7, so the
  // block (0.1 <= z <= 0.9) is scaled by 0.7 in z.
  const Eigen::MatrixX3d& rest = scene.findObject("block")->mesh.points;
  EXPECT_NEAR(points.col(2).maxCoeff(), 0.7 * rest.col(2).maxCoeff(), 1e-9);
  EXPECT_NEAR(points.col(2).minCoeff(), 0.7 * rest.col(2).minCoeff(), 1e-9);
  const auto dir = std::filesystem::temp_directory_path() / "ffdkit-readme-example";
  std::filesystem::create_directories(dir);
  scenes::writeMesh(dir / "block.ply", {points, scene.findObject("block")->mesh.triangles, {}, true});
  EXPECT_EQ(scenes::readMesh(dir / "block.ply").points.rows(), points.rows());
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ffdkit
