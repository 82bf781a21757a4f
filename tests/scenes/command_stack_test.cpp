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
  EXPECT_THROW(stack.push(Command{"nothing", {}, {}, "", 0}), std::invalid_argument);
  EXPECT_THROW(CommandStack(0), std::invalid_argument);
}

// Typing a value: every keystroke is a command with the same merge key; one undo step.
TEST(CommandStack, ConsecutiveEditsOfOneFieldMergeIntoOneStep) {
  Document doc;
  CommandStack stack;
  setValue(stack, doc, 0, 7);  // no key: its own step
  auto typed = [&](int value) {
    const int before = doc.values[1];
    doc.values[1] = value;
    stack.push(Command{"type " + std::to_string(value), [&doc, before] { doc.values[1] = before; },
                       [&doc, value] { doc.values[1] = value; }, "value/1", sizeof(int)});
  };
  typed(1);
  typed(12);
  typed(123);
  EXPECT_EQ(stack.size(), 2u);
  EXPECT_EQ(stack.undoDescription(), "type 123");
  EXPECT_EQ(stack.bytes(), 2 * sizeof(std::vector<int>) + 3 * sizeof(int));
  stack.undo();
  EXPECT_EQ(doc.values, (std::vector<int>{7, 0, 0}));
  stack.redo();
  EXPECT_EQ(doc.values, (std::vector<int>{7, 123, 0}));
  // A save between two edits keeps them apart; so does another key.
  stack.markClean();
  typed(5);
  EXPECT_EQ(stack.size(), 3u);
  stack.undo();
  EXPECT_EQ(doc.values, (std::vector<int>{7, 123, 0}));
  EXPECT_FALSE(stack.isDirty());
}

}  // namespace
}  // namespace ffdkit::scenes
