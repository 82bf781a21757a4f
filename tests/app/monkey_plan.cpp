#include "monkey_plan.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <random>
#include <string_view>

#include <QKeySequence>
#include <QString>

#include "keyboard_shortcuts.h"

namespace ffdkit::app::testing {

namespace {

// Actions that replace the document or leave the program: not in the plan (a segment's undo
// goes back to the scene it opened). Save is in it: it writes the temporary copy.
constexpr std::array<std::string_view, 4> kLeavingActions{"actionNewScene", "actionOpenScene", "actionSaveSceneAs",
                                                          "actionQuit"};

// std::mt19937_64's sequence is the same everywhere; the standard distributions are not, so
// numbers are drawn from it by hand.
class Draw {
 public:
  explicit Draw(std::uint64_t seed) : engine_(seed) {}
  std::uint32_t any() { return static_cast<std::uint32_t>(engine_() >> 32); }
  int below(int n) { return static_cast<int>(engine_() % static_cast<std::uint64_t>(n)); }
  double fraction() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  bool chance(double p) { return fraction() < p; }

 private:
  std::mt19937_64 engine_;
};

MonkeyKey keyOf(const char* portableText) {
  const QKeySequence sequence(QString::fromLatin1(portableText), QKeySequence::PortableText);
  return {sequence[0].key(), sequence[0].keyboardModifiers()};
}

// Every key of the shortcut table (but the leaving ones), and the keys typed into a value.
const std::vector<MonkeyKey>& monkeyKeys() {
  static const std::vector<MonkeyKey> keys = [] {
    std::vector<MonkeyKey> all;
    for (const KeyboardShortcut& s : keyboardShortcuts())
      if (std::find(kLeavingActions.begin(), kLeavingActions.end(), std::string_view(s.action)) == kLeavingActions.end())
        all.push_back(keyOf(s.keys));
    for (int digit = 0; digit <= 9; ++digit) all.push_back({static_cast<Qt::Key>(Qt::Key_0 + digit), Qt::NoModifier});
    for (Qt::Key k : {Qt::Key_Minus, Qt::Key_Period, Qt::Key_Comma, Qt::Key_Enter, Qt::Key_Escape, Qt::Key_Delete})
      all.push_back({k, Qt::NoModifier});
    return all;
  }();
  return keys;
}

Qt::KeyboardModifiers drawModifiers(Draw& draw) {
  switch (draw.below(10)) {
    case 0: return Qt::ShiftModifier;
    case 1: return Qt::ControlModifier;
    case 2: return Qt::AltModifier;
    default: return Qt::NoModifier;
  }
}

void drawPositions(Draw& draw, MonkeyAction& a) {
  a.x0 = draw.fraction();
  a.y0 = draw.fraction();
  a.x1 = draw.fraction();
  a.y1 = draw.fraction();
}

// G / R / S, maybe an axis, maybe a typed value, the pointer moves, then Enter, Esc or a click.
void drawModalTransform(Draw& draw, MonkeyAction& a) {
  a.keys.push_back(keyOf(std::array{"G", "R", "S"}[static_cast<std::size_t>(draw.below(3))]));
  if (draw.chance(0.5))
    a.keys.push_back(keyOf(std::array{"X", "Y", "Z", "Shift+X", "Shift+Y", "Shift+Z"}[static_cast<std::size_t>(draw.below(6))]));
  if (draw.chance(0.4)) {
    const std::string_view value = std::array{"0.5", "-1", "90", "2", "0", "1,0,0", "-0.25", "1e"}[static_cast<std::size_t>(draw.below(8))];
    for (char c : value) {
      if (c == 'e') a.keys.push_back({Qt::Key_Backspace, Qt::NoModifier});  // a correction
      else if (c == '.') a.keys.push_back({Qt::Key_Period, Qt::NoModifier});
      else if (c == '-') a.keys.push_back({Qt::Key_Minus, Qt::NoModifier});
      else if (c == ',') a.keys.push_back({Qt::Key_Comma, Qt::NoModifier});
      else a.keys.push_back({static_cast<Qt::Key>(Qt::Key_0 + (c - '0')), Qt::NoModifier});
    }
  }
  a.moves = draw.below(6);
  const int end = draw.below(20);
  if (end < 7) a.keys.push_back({Qt::Key_Return, Qt::NoModifier});
  else if (end < 12) a.keys.push_back({Qt::Key_Escape, Qt::NoModifier});
  else a.endsWithClick = true, a.button = end < 17 ? Qt::LeftButton : Qt::RightButton;
}

MonkeyAction drawAction(Draw& draw) {
  // Weights out of 100: the 3D view's pointer most, then keys, undo / redo, menus and panels.
  struct Weight {
    MonkeyKind kind;
    int weight;
  };
  constexpr std::array<Weight, 15> kWeights{{{MonkeyKind::Click, 9},
                                             {MonkeyKind::Drag, 9},
                                             {MonkeyKind::Hover, 4},
                                             {MonkeyKind::GlyphClick, 8},
                                             {MonkeyKind::GlyphDrag, 12},
                                             {MonkeyKind::ObjectDrag, 4},
                                             {MonkeyKind::Key, 14},
                                             {MonkeyKind::ModalTransform, 6},
                                             {MonkeyKind::Undo, 7},
                                             {MonkeyKind::Redo, 4},
                                             {MonkeyKind::MenuAction, 8},
                                             {MonkeyKind::ToolbarButton, 3},
                                             {MonkeyKind::OutlinerClick, 5},
                                             {MonkeyKind::Timeline, 2},
                                             {MonkeyKind::PanelEdit, 5}}};
  int roll = draw.below(100);
  MonkeyAction a;
  for (const Weight& w : kWeights) {
    if (roll < w.weight) {
      a.kind = w.kind;
      break;
    }
    roll -= w.weight;
  }
  drawPositions(draw, a);
  a.pick = draw.any();
  a.pick2 = draw.any();
  a.answer = draw.any();
  a.moves = 1 + draw.below(12);
  switch (a.kind) {
    case MonkeyKind::Click:
    case MonkeyKind::Drag: {
      const int b = draw.below(20);
      a.button = b < 17 ? Qt::LeftButton : b < 19 ? Qt::RightButton : Qt::MiddleButton;
      a.modifiers = drawModifiers(draw);
      break;
    }
    case MonkeyKind::GlyphClick:
    case MonkeyKind::GlyphDrag:
    case MonkeyKind::ObjectDrag:
    case MonkeyKind::OutlinerClick: a.modifiers = drawModifiers(draw); break;
    case MonkeyKind::Key: a.keys.push_back(monkeyKeys()[static_cast<std::size_t>(draw.below(static_cast<int>(monkeyKeys().size())))]); break;
    case MonkeyKind::ModalTransform: drawModalTransform(draw, a); break;
    case MonkeyKind::Undo: a.keys.push_back(keyOf("Ctrl+Z")); break;
    case MonkeyKind::Redo: a.keys.push_back(keyOf("Ctrl+Shift+Z")); break;
    default: break;
  }
  return a;
}

std::string modifiersText(Qt::KeyboardModifiers m) {
  std::string text;
  if (m & Qt::ControlModifier) text += "Ctrl+";
  if (m & Qt::ShiftModifier) text += "Shift+";
  if (m & Qt::AltModifier) text += "Alt+";
  if (m & Qt::KeypadModifier) text += "Num+";
  return text;
}

std::string point(double x, double y) {
  char text[48];
  std::snprintf(text, sizeof text, "(%.3f, %.3f)", x, y);
  return text;
}

std::string buttonText(Qt::MouseButton b) {
  return b == Qt::LeftButton ? "left" : b == Qt::RightButton ? "right" : "middle";
}

}  // namespace

std::vector<MonkeySegment> monkeyPlan(std::uint64_t seed, int count, const std::vector<std::string>& scenes) {
  std::vector<MonkeySegment> plan;
  if (scenes.empty() || count <= 0) return plan;
  Draw draw(seed);
  // Every scene once before any twice when the count allows at least 25 actions each.
  const int perScene = (count + static_cast<int>(scenes.size()) - 1) / static_cast<int>(scenes.size());
  const int length = std::clamp(perScene, 25, kMaxSegmentActions);
  const std::size_t first = seed % scenes.size();
  for (int done = 0; done < count;) {
    MonkeySegment segment;
    segment.scene = scenes[(first + plan.size()) % scenes.size()];
    const int n = std::min(length, count - done);
    for (int i = 0; i < n; ++i) segment.actions.push_back(drawAction(draw));
    done += n;
    plan.push_back(std::move(segment));
  }
  return plan;
}

std::string describe(const MonkeyKey& key) {
  return modifiersText(key.modifiers) +
         QKeySequence(QKeyCombination(Qt::NoModifier, key.key)).toString(QKeySequence::PortableText).toStdString();
}

std::string describe(const MonkeyAction& a) {
  const std::string mods = a.modifiers == Qt::NoModifier ? "" : ", " + modifiersText(a.modifiers);
  const std::string offset = point(a.x1 - 0.5, a.y1 - 0.5);
  switch (a.kind) {
    case MonkeyKind::Click: return buttonText(a.button) + " click at " + point(a.x0, a.y0) + mods;
    case MonkeyKind::Drag:
      return buttonText(a.button) + " drag " + point(a.x0, a.y0) + " -> " + point(a.x1, a.y1) + " in " +
             std::to_string(a.moves) + " moves" + mods;
    case MonkeyKind::Hover: return "hover at " + point(a.x0, a.y0);
    case MonkeyKind::GlyphClick: return "click on glyph #" + std::to_string(a.pick) + "/" + std::to_string(a.pick2) + mods;
    case MonkeyKind::GlyphDrag:
      return "drag glyph #" + std::to_string(a.pick) + "/" + std::to_string(a.pick2) + " by " + offset + " in " +
             std::to_string(a.moves) + " moves" + mods;
    case MonkeyKind::ObjectDrag:
      return "drag object point #" + std::to_string(a.pick) + "/" + std::to_string(a.pick2) + " by " + offset + mods;
    case MonkeyKind::Key:
    case MonkeyKind::Undo:
    case MonkeyKind::Redo: return "key " + describe(a.keys.front());
    case MonkeyKind::ModalTransform: {
      std::string text = "modal transform:";
      for (std::size_t i = 0; i + (a.endsWithClick ? 0 : 1) < a.keys.size(); ++i) text += " " + describe(a.keys[i]);
      text += ", " + std::to_string(a.moves) + " moves to " + point(a.x0, a.y0) + ", then ";
      return text + (a.endsWithClick ? buttonText(a.button) + " click" : describe(a.keys.back()));
    }
    case MonkeyKind::MenuAction: return "menu action #" + std::to_string(a.pick);
    case MonkeyKind::ToolbarButton: return "toolbar button #" + std::to_string(a.pick);
    case MonkeyKind::OutlinerClick:
      return std::string(a.pick2 % 10 == 0 ? "double click" : "click") + " on outliner row #" + std::to_string(a.pick) + mods;
    case MonkeyKind::Timeline: {
      char text[96];
      std::snprintf(text, sizeof text, "timeline #%u at %.3f -> %.3f", a.pick, a.x0, a.x1);
      return text;
    }
    case MonkeyKind::PanelEdit: return "property panel field #" + std::to_string(a.pick) + ", edit " + std::to_string(a.pick2 % 8);
  }
  return "?";
}

}  // namespace ffdkit::app::testing
