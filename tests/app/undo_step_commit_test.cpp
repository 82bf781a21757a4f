// An undo step is pushed only for a change that holds. An edit (InteractionController::edit), a
// transform's confirm (EditController::confirm) and a drag's release
// (InteractionController::release) evaluate the change first; when that throws
// (here the deformer's progress hook cancels the evaluation, as Cancel in the embedding's
// progress dialog does) the change is taken back and the command stack is as it was: no step
// whose undo would undo nothing, and the steps that could be redone are still there.
#include <gtest/gtest.h>

#include <string>

#include "arrow_ray.h"
#include "ffdkit/ffd/cancelled.h"
#include "ffdkit/interaction/edit_controller.h"
#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/scene_file.h"

namespace ffdkit::app {
namespace {

using widgets::WidgetId;

struct Document {
  scenes::Scene scene = scenes::readScene(FFDKIT_SOURCE_DIR "/scenes/examples/mirror");
  scenes::SceneDeformer deformer;
  scenes::CommandStack commands;
  InteractionController controller{scene, deformer, commands};
  EditController edit{scene, deformer, commands, controller};
};

/// What the stack holds: its position, size and the step an undo and a redo would run.
std::string stackText(const scenes::CommandStack& c) {
  return std::to_string(c.position()) + "/" + std::to_string(c.size()) + " undo '" + c.undoDescription() + "' redo '" +
         c.redoDescription() + "'";
}

/// Two edits, the second undone: a step to undo and one to redo.
void twoEditsOneUndone(Document& d) {
  d.deformer.evaluate(d.scene);
  d.controller.setVariation(d.scene.widgets.find("turn-front"), 0.2);
  d.controller.setVariation(d.scene.widgets.find("pull-back"), 0.1);
  d.commands.undo();
  ASSERT_EQ(stackText(d.commands), "1/2 undo 'Set variation of turn-front' redo 'Set variation of pull-back'");
}

TEST(UndoStepCommit, AnEditWhoseEvaluationThrowsLeavesNoUndoStep) {
  Document d;
  twoEditsOneUndone(d);
  const std::string scene = scenes::sceneFileText(d.scene), stack = stackText(d.commands);
  d.deformer.setProgress([](double) { return false; });  // Cancel: every evaluation with work throws
  EXPECT_THROW(d.controller.setVariation(d.scene.widgets.find("push-front"), 0.3), ffd::Cancelled);
  EXPECT_TRUE(scenes::sceneFileText(d.scene) == scene) << "the edit is taken back";
  EXPECT_EQ(stackText(d.commands), stack) << "no step for it, and the redo kept";
  d.deformer.setProgress({});
  d.commands.redo();
  EXPECT_EQ(d.scene.widgets.variation(d.scene.widgets.find("pull-back")), 0.1);
  EXPECT_EQ(d.scene.widgets.variation(d.scene.widgets.find("push-front")), 0.0);
}

TEST(UndoStepCommit, ATransformWhoseEvaluationThrowsAtConfirmLeavesNoUndoStep) {
  Document d;
  twoEditsOneUndone(d);
  const std::string scene = scenes::sceneFileText(d.scene), stack = stackText(d.commands);
  const WidgetId lattice = d.scene.widgets.find("lattice");
  d.edit.enter(lattice);
  d.edit.pickMany({0, 1}, SelectMode::Replace);
  widgets::Ray ray;
  ray.origin = *d.edit.pivotPoint() + Eigen::Vector3d(0, 0, 10);
  ray.direction = {0, 0, -1};
  d.edit.beginModal(TransformMode::Move, ray, {0, 0, -1});
  d.edit.modal()->setConstraint({0, false});
  for (char c : std::string("0.25")) d.edit.modal()->typed().type(c);
  d.edit.update(ray, false);
  ASSERT_TRUE(scenes::sceneFileText(d.scene) != scene) << "the transform moved the points";
  d.deformer.setProgress([](double) { return false; });
  EXPECT_THROW(d.edit.confirm(), ffd::Cancelled);
  EXPECT_FALSE(d.edit.transforming());
  EXPECT_TRUE(scenes::sceneFileText(d.scene) == scene) << "the transform is taken back";
  EXPECT_EQ(stackText(d.commands), stack) << "no step for it, and the redo kept";
  d.deformer.setProgress({});
  // The same transform confirmed without the hook is one step, undone to the scene before it.
  d.edit.beginModal(TransformMode::Move, ray, {0, 0, -1});
  d.edit.modal()->setConstraint({0, false});
  for (char c : std::string("0.25")) d.edit.modal()->typed().type(c);
  d.edit.update(ray, false);
  d.edit.confirm();
  EXPECT_EQ(stackText(d.commands), "2/2 undo 'Move 2 points of lattice' redo ''");
  d.commands.undo();
  EXPECT_TRUE(scenes::sceneFileText(d.scene) == scene) << "undo of the transform";
}

// A drag of the translate widget `push-front`'s arrow by `shift` glyph sizes along it: press on
// the arrow's middle, down its frame's z (WidgetModel::pick's shape), two moves.
void pressAndDragPushFront(Document& d, double shift) {
  const WidgetId push = d.scene.widgets.find("push-front");
  ASSERT_EQ(d.scene.widgets.affineKind(push), widgets::AffineKind::Translate);
  const auto rayAt = [&](double along) { return test::arrowRay(d.scene.widgets, push, along); };
  ASSERT_EQ(d.controller.press(rayAt(0.5), test::arrowTolerance(d.scene.widgets, push)), InteractionController::PressResult::Widget);
  d.controller.drag(rayAt(0.5 + 0.5 * shift));
  d.controller.drag(rayAt(0.5 + shift));
}

TEST(UndoStepCommit, ADragWhoseEvaluationThrowsAtReleaseLeavesNoUndoStep) {
  Document d;
  twoEditsOneUndone(d);
  const std::string scene = scenes::sceneFileText(d.scene), stack = stackText(d.commands);
  pressAndDragPushFront(d, 0.5);
  ASSERT_TRUE(scenes::sceneFileText(d.scene) != scene) << "the drag moved the widget";
  d.deformer.setProgress([](double) { return false; });  // Cancel: the release's exact evaluation throws
  EXPECT_THROW(d.controller.release(), ffd::Cancelled);
  EXPECT_FALSE(d.controller.dragging());
  EXPECT_TRUE(scenes::sceneFileText(d.scene) == scene) << "the drag is taken back";
  EXPECT_EQ(stackText(d.commands), stack) << "no step for it, and the redo kept";
  d.deformer.setProgress({});
  // The same drag released without the hook is one step, undone to the scene before it.
  pressAndDragPushFront(d, 0.5);
  d.controller.release();
  EXPECT_EQ(stackText(d.commands), "2/2 undo 'Drag push-front' redo ''");
  d.commands.undo();
  EXPECT_TRUE(scenes::sceneFileText(d.scene) == scene) << "undo of the drag";
}

}  // namespace
}  // namespace ffdkit::app
