#pragma once

// The monkey test's plan: a seeded list of random GUI actions (clicks, drags, keys, menu actions,
// undo / redo, outliner rows, the timeline, the property panel) over a rotation of the sample
// scenes. The plan is a pure function of (seed, count): printing it (monkey_gui_test --replay)
// and running it give the same list, so a failure is reproduced by its seed. What an action
// aims at (which glyph, which outliner row, which menu action) is drawn as a number and taken
// modulo what the window has when the action runs.

#include <cstdint>
#include <string>
#include <vector>

#include <Qt>

namespace ffdkit::app::testing {

enum class MonkeyKind {
  Click,           ///< a click in the 3D view at (x0, y0)
  Drag,            ///< a drag in the 3D view from (x0, y0) to (x1, y1)
  Hover,           ///< the pointer moves over the 3D view to (x0, y0), no button down
  GlyphClick,      ///< a click on a widget's glyph (a lattice point, a cell, an affine widget's axis)
  GlyphDrag,       ///< a drag from a widget's glyph by (x1 - 0.5, y1 - 0.5) of the view's size
  ObjectDrag,      ///< a drag from one of an object's (deformed) points
  Key,             ///< a key of the shortcut table or one typed into a value
  ModalTransform,  ///< G / R / S, maybe an axis and a typed value, pointer moves, then an end key or click
  Undo,            ///< Ctrl+Z
  Redo,            ///< Ctrl+Shift+Z
  MenuAction,      ///< an action of the menu bar, opened and clicked with the mouse
  ToolbarButton,   ///< a click on a toolbar button
  OutlinerClick,   ///< a click (or double click) on an outliner row
  Timeline,        ///< a click or drag on the timeline's ruler, or a click on one of its buttons
  PanelEdit,       ///< a property panel field: spin box, combo box, check box, line edit or button
};

struct MonkeyKey {
  Qt::Key key = Qt::Key_unknown;
  Qt::KeyboardModifiers modifiers = Qt::NoModifier;
};

/// One action. Positions are fractions of the target widget's size; `pick` and `pick2` choose
/// among what exists when it runs; `answer` seeds the answers to any dialog it opens.
struct MonkeyAction {
  MonkeyKind kind = MonkeyKind::Click;
  double x0 = 0.5, y0 = 0.5, x1 = 0.5, y1 = 0.5;
  int moves = 1;  ///< pointer moves of a drag, or of a modal transform
  std::uint32_t pick = 0, pick2 = 0;
  Qt::MouseButton button = Qt::LeftButton;
  Qt::KeyboardModifiers modifiers = Qt::NoModifier;
  std::vector<MonkeyKey> keys;  ///< Key: one key; ModalTransform: the keys in order (the end key last)
  bool endsWithClick = false;   ///< ModalTransform: a left (or right) click ends it instead of a key
  std::uint32_t answer = 0;
};

/// A part of the plan on one sample scene: opened at the start, undone to its file at the end.
struct MonkeySegment {
  std::string scene;  ///< a folder name of scenes/examples
  std::vector<MonkeyAction> actions;
};

/// Commands a segment may push at most: less than the command stack's limit (1000), so undo
/// always reaches the opened file.
constexpr int kMaxSegmentActions = 400;

/// The plan: `count` actions over segments of at most kMaxSegmentActions, each on the next
/// scene of `scenes` (a rotation that starts at seed % scenes.size()).
std::vector<MonkeySegment> monkeyPlan(std::uint64_t seed, int count, const std::vector<std::string>& scenes);

/// "drag (0.31, 0.52) -> (0.70, 0.11) in 6 moves, Shift" (menu actions and targets by number).
std::string describe(const MonkeyAction& action);
std::string describe(const MonkeyKey& key);

}  // namespace ffdkit::app::testing
