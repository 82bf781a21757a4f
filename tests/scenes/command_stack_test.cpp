#include "ffdkit/scenes/command_stack.h"

#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace ffdkit::scenes {
namespace {

// A tiny document: a vector of numbers changed by commands that set one entry.
struct Document {
  std::vector<int> values{0, 0, 0};
};

void setValue(CommandStack& stack, Document& doc, std::size_t i, int value) {
  const std::vector<int> before = doc.values;
  doc.values[i] = value;
  stack.pushSnapshots("set " + std::to_string(i), before, doc.values,
                      [&doc](const std::vector<int>& state) { doc.values = state; });
}

TEST(CommandStack, UndoRedoWalkThroughTheStates) {
  Document doc;
  CommandStack stack;
  setValue(stack, doc, 0, 1);
  setValue(stack, doc, 1, 2);
  setValue(stack, doc, 2, 3);
  EXPECT_EQ(doc.values, (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(stack.undoDescription(), "set 2");
  stack.undo();
  stack.undo();
  EXPECT_EQ(doc.values, (std::vector<int>{1, 0, 0}));
  EXPECT_EQ(stack.redoDescription(), "set 1");
  stack.redo();
  EXPECT_EQ(doc.values, (std::vector<int>{1, 2, 0}));
  stack.undo();
  stack.undo();
  EXPECT_EQ(doc.values, (std::vector<int>{0, 0, 0}));
  EXPECT_FALSE(stack.canUndo());
  EXPECT_THROW(stack.undo(), std::logic_error);
}

TEST(CommandStack, PushAfterUndoDropsTheRedoBranch) {
  Document doc;
  CommandStack stack;
  setValue(stack, doc, 0, 1);
  setValue(stack, doc, 0, 2);
  stack.undo();
  setValue(stack, doc, 1, 5);
  EXPECT_FALSE(stack.canRedo());
  EXPECT_EQ(stack.size(), 2u);
  EXPECT_THROW(stack.redo(), std::logic_error);
  stack.undo();
  stack.undo();
  EXPECT_EQ(doc.values, (std::vector<int>{0, 0, 0}));
}

TEST(CommandStack, TracksTheCleanStateAcrossUndoAndRedo) {
  Document doc;
  CommandStack stack;
  EXPECT_FALSE(stack.isDirty());
  setValue(stack, doc, 0, 1);
  EXPECT_TRUE(stack.isDirty());
  stack.markClean();
  setValue(stack, doc, 0, 2);
  EXPECT_TRUE(stack.isDirty());
  stack.undo();
  EXPECT_FALSE(stack.isDirty());
  stack.undo();
  EXPECT_TRUE(stack.isDirty());
  stack.redo();
  setValue(stack, doc, 1, 1);  // replaces nothing clean: the clean state is still reachable
  EXPECT_TRUE(stack.isDirty());
  stack.undo();
  EXPECT_FALSE(stack.isDirty());
}

TEST(CommandStack, KeepsAtMostLimitCommands) {
  Document doc;
  CommandStack stack(2);
  int notifications = 0;
  stack.onChanged = [&] { ++notifications; };
  setValue(stack, doc, 0, 1);
  setValue(stack, doc, 0, 2);
  setValue(stack, doc, 0, 3);
  EXPECT_EQ(stack.size(), 2u);
  stack.undo();
  stack.undo();
  EXPECT_EQ(doc.values[0], 1);  // the first change was dropped and cannot be undone
  EXPECT_FALSE(stack.canUndo());
  EXPECT_EQ(notifications, 5);
}

TEST(CommandStack, RejectsIncompleteCommands) {
  CommandStack stack;
  EXPECT_THROW(stack.push(Command{"nothing", {}, {}}), std::invalid_argument);
  EXPECT_THROW(CommandStack(0), std::invalid_argument);
}

}  // namespace
}  // namespace ffdkit::scenes
