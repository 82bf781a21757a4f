// Control-point weights (rational lattices, Lamousin & Waggenspack 1994) through the widget
// model, its undo state, widget and scene files, and the scene deformer.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "ffdkit/scenes/document_delta.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/scene_file.h"
#include "ffdkit/scenes/widget_file.h"
#include "scenes_test_support.h"

namespace ffdkit::scenes {
namespace {

using widgets::WidgetError;
using widgets::WidgetId;
using widgets::WidgetModel;

const std::filesystem::path kSource = FFDKIT_SOURCE_DIR;

std::string weightsErrorOf(const std::string& text) {
  std::istringstream in(text);
  try {
    readWidgetFile(in, "tool.json");
  } catch (const WidgetFileError& e) {
    return e.what();
  }
  return "no error";
}

// The text of a one-lattice tool with `weights` spliced into its lattice (and `version`).
std::string toolText(const std::string& weights, int version) {
  WidgetModel model;
  model.addLattice("box", Eigen::Vector3i(2, 2, 2));
  std::string text = widgetFileText(model);
  const std::string points = "\"points\":";
  text.insert(text.find(points), "\"weights\": " + weights + ", ");
  const std::string v1 = "\"version\": 1";
  EXPECT_NE(text.find(v1), std::string::npos);
  text.replace(text.find(v1), v1.size(), "\"version\": " + std::to_string(version));
  return text;
}

TEST(RationalWeights, TheModelEditsWeightsAsControlEditsWithUndo) {
  WidgetModel model;
  const WidgetId lattice = model.addLattice("box", Eigen::Vector3i(3, 3, 3));
  EXPECT_FALSE(model.isRational(lattice));
  EXPECT_EQ(model.weights(lattice), Eigen::VectorXd::Ones(27));
  const widgets::WidgetModelState before = model.captureState();
  const std::uint64_t control = model.controlRevision(lattice);
  model.setWeight(lattice, 13, 2.5);
  EXPECT_GT(model.controlRevision(lattice), control);
  EXPECT_TRUE(model.isRational(lattice));
  EXPECT_EQ(model.ffdLattice(lattice).weight(13), 2.5);
  const widgets::WidgetModelState after = model.captureState();
  const StateDelta delta = stateDelta(before, after);
  EXPECT_FALSE(delta.empty());
  ASSERT_EQ(delta.after.weights.size(), 1u);
  model.restoreState(delta.before);  // undo
  EXPECT_FALSE(model.isRational(lattice));
  model.restoreState(delta.after);  // redo
  EXPECT_EQ(model.weights(lattice)[13], 2.5);
  // Bad weights are refused and change nothing.
  EXPECT_THROW(model.setWeight(lattice, 13, 0.0), WidgetError);
  EXPECT_THROW(model.setWeight(lattice, 27, 1.0), WidgetError);
  EXPECT_THROW(model.setWeights(lattice, Eigen::VectorXd::Ones(26)), WidgetError);
  EXPECT_EQ(model.weights(lattice)[13], 2.5);
  model.resetLattice(lattice);
  EXPECT_FALSE(model.isRational(lattice));
}

// A document edit's command holds the records that changed (modelPatch): a weight edit alone is
// a change of its lattice's record, so its undo gives the polynomial lattice back and its redo
// the weight (found by the monkey GUI test: the undo of 'Weight of point 5 of lattice' did nothing).
TEST(RationalWeights, AWeightEditAloneIsAPatchOfItsLattice) {
  WidgetModel model;
  const WidgetId lattice = model.addLattice("box", Eigen::Vector3i(3, 3, 3));
  const widgets::WidgetModelData before = model.toData();
  model.setWeight(lattice, 5, 0.5);
  const ModelPatch patch = modelPatch(before, model.toData());
  ASSERT_EQ(patch.lattices.size(), 1u);
  EXPECT_GT(patch.bytes(), 27 * sizeof(double));  // the weights are held, not only the points
  applyPatch(model, patch, false);  // undo
  EXPECT_FALSE(model.isRational(lattice));
  EXPECT_EQ(widgetFileText(model).find("\"version\": 2"), std::string::npos);
  applyPatch(model, patch, true);  // redo
  EXPECT_EQ(model.weights(lattice)[5], 0.5);
}

TEST(RationalWeights, WidgetFilesCarryWeightsInVersionTwoOnly) {
  WidgetModel model;
  const WidgetId lattice = model.addLattice("box", Eigen::Vector3i(3, 2, 2));
  const std::string plain = widgetFileText(model);
  EXPECT_NE(plain.find("\"version\": 1"), std::string::npos);
  EXPECT_EQ(plain.find("weights"), std::string::npos);
  Eigen::VectorXd w = Eigen::VectorXd::Ones(12);
  w[1] = 1.0 / std::sqrt(2.0);
  w[7] = 3.25;
  model.setWeights(lattice, w);
  const std::string weighted = widgetFileText(model);
  EXPECT_NE(weighted.find("\"version\": 2"), std::string::npos);
  std::istringstream in(weighted);
  const WidgetModel back = readWidgetFile(in, "tool.json");
  EXPECT_EQ(back.weights(back.find("box")), w);  // every bit: JSON numbers keep doubles exactly
  EXPECT_EQ(widgetFileText(back), weighted);
  // Weights back to 1: written as version 1 again, the same bytes as before.
  model.setWeights(lattice, Eigen::VectorXd::Ones(12));
  EXPECT_EQ(widgetFileText(model), plain);
}

TEST(RationalWeights, EverySampleToolIsWrittenAsItWasRead) {
  for (const auto& entry : std::filesystem::directory_iterator(kSource / "widgets/examples")) {
    if (entry.path().extension() != ".json") continue;
    const WidgetModel model = readWidgetFile(entry.path());
    std::ifstream in(entry.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(widgetFileText(model), text) << entry.path();
  }
}

TEST(RationalWeights, BadWeightsAreErrorsAtTheirPointer) {
  EXPECT_NE(weightsErrorOf(toolText("[1, 1, 1, 1, 1, 1, 1, 2]", 2)).find("no error"), std::string::npos);
  EXPECT_NE(weightsErrorOf(toolText("[1, 1, 1, 1, 1, 1, 1, 2]", 1)).find("/lattices/0/weights: 'weights' needs widget file version 2"),
            std::string::npos);
  EXPECT_NE(weightsErrorOf(toolText("[1, 1, 1, 0, 1, 1, 1, 1]", 2)).find("/lattices/0/weights/3: a weight must be > 0, got 0"),
            std::string::npos);
  EXPECT_NE(weightsErrorOf(toolText("[1, 1, 1, -2.5, 1, 1, 1, 1]", 2)).find("/lattices/0/weights/3"), std::string::npos);
  EXPECT_NE(weightsErrorOf(toolText("[1, 1, 1]", 2)).find("/lattices/0/weights: expected 8 weights (one per control point), got 3"),
            std::string::npos);
  EXPECT_NE(weightsErrorOf(toolText("[1, 1, 1, \"x\", 1, 1, 1, 1]", 2)).find("/lattices/0/weights/3: expected a number"),
            std::string::npos);
  EXPECT_NE(weightsErrorOf(toolText("2", 2)).find("/lattices/0/weights"), std::string::npos);
  EXPECT_NE(weightsErrorOf(toolText("[1, 1, 1, 1, 1, 1, 1, 1]", 3)).find("newer than this build reads (2)"), std::string::npos);
}

TEST(RationalWeights, ScenesRoundTripAndDeformWithWeights) {
  Scene scene = readScene(kSource / "scenes/examples/press");
  const WidgetId lattice = scene.widgets.widgets(widgets::WidgetType::Lattice).front();
  SceneDeformer deformer;
  deformer.evaluate(scene);
  const std::string object = scene.objects().front().name;
  const Eigen::MatrixX3d plain = deformer.points(object);
  const Eigen::Index n = scene.widgets.weights(lattice).size();
  scene.widgets.setWeight(lattice, n / 2, 4.0);
  deformer.evaluate(scene);
  const Eigen::MatrixX3d weighted = deformer.points(object);
  EXPECT_GT((weighted - plain).cwiseAbs().maxCoeff(), 1e-6);  // the weight pulls the shape
  // The same result from a fresh deformer (no incremental state) and after a file round trip.
  SceneDeformer fresh;
  fresh.evaluate(scene);
  EXPECT_LE((fresh.points(object) - weighted).cwiseAbs().maxCoeff(), 1e-12);
  const std::string text = sceneFileText(scene);
  std::istringstream in(text);
  Scene back = readScene(in, "scene.json", SceneReadOptions{.baseDirectory = kSource / "scenes/examples/press"});
  EXPECT_EQ(back.widgets.weights(back.widgets.widgets(widgets::WidgetType::Lattice).front())[n / 2], 4.0);
  EXPECT_EQ(sceneFileText(back), text);
  SceneDeformer reread;
  reread.evaluate(back);
  EXPECT_LE((reread.points(object) - weighted).cwiseAbs().maxCoeff(), 1e-12);
}

}  // namespace
}  // namespace ffdkit::scenes
