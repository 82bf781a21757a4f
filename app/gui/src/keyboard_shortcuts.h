// The one home of ffdkit's keyboard shortcuts: a table of (keys, action, context, description)
// that the window's actions take their shortcuts from (applyKeyboardShortcuts), that the view's
// own key handling checks events against (matchesShortcut), that Help > Keyboard Shortcuts
// shows, and that docs/app.md must list row for row (tests/app/keyboard_shortcuts_test.cpp).
#pragma once

#include <span>
#include <string>
#include <string_view>

#include <QKeySequence>
#include <QList>
#include <QString>

class QKeyEvent;
class QObject;
class QWidget;

namespace ffdkit::app {

/// Where (in which mode) a shortcut acts.
enum class ShortcutContext {
  Window,    ///< anywhere in the window (a menu action)
  View,      ///< the 3D view's camera (a View menu action, anywhere in the window)
  Drag,      ///< while a drag is under way in the 3D view
  EditMode,  ///< lattice edit mode
};

/// One row of the table.
struct KeyboardShortcut {
  /// QKeySequence portable text: "Ctrl+Shift+Z", "Del", "F2", "Num+1" (the keypad's 1 only).
  const char* keys;
  /// The object name of the QAction it triggers ("actionUndo"), or, for a key the 3D view
  /// handles itself (not a QAction, name not starting with "action"), the name its handler
  /// checks with matchesShortcut ("cancelDrag").
  const char* action;
  ShortcutContext context;
  /// What it does, as Help > Keyboard Shortcuts and docs/app.md say it.
  const char* description;
};

/// Every row, in the order Help and docs/app.md list them. An action may have several rows
/// (several keys); two rows never share keys within one context (Window and View count as one).
std::span<const KeyboardShortcut> keyboardShortcuts();

/// The keys of every row of `action`, in table order (empty if it has none).
QList<QKeySequence> shortcutsOf(std::string_view action);

/// Whether the key event is one of `action`'s keys. A row without "Num+" also matches the
/// keypad's key of the same name (as Qt's shortcut map does); a "Num+" row only the keypad's.
bool matchesShortcut(const QKeyEvent& event, std::string_view action);

/// `tip` followed by `action`'s keys as a person reads them, "Undo (Ctrl+Z)", "Frame the
/// selection (F, Numpad .)"; `tip` alone when the action has no keys. The one way a tooltip
/// names keys, so a tooltip cannot disagree with the table.
QString withShortcutText(const QString& tip, std::string_view action);

/// Gives every QAction below `root` named in the table its keys (QAction::setShortcuts), and
/// its tooltip the keys (withShortcutText).
/// @throws std::logic_error naming the row when a row's action ("action...") is not found, so a
///   renamed action cannot silently lose its keys.
void applyKeyboardShortcuts(QObject* root);

/// The keys as a person reads them: "Ctrl+Shift+Z", "Numpad 1", "Numpad .".
QString shortcutKeysText(const KeyboardShortcut& shortcut);
/// "anywhere", "3D view", "while dragging", "lattice edit mode".
QString shortcutContextText(ShortcutContext context);
/// The row as docs/app.md writes it: "| keys | context | description |".
std::string shortcutMarkdownRow(const KeyboardShortcut& shortcut);

/// Help > Keyboard Shortcuts: a (non-modal) dialog listing the table, object name
/// "keyboardShortcutsDialog", its table "shortcutsTable" (columns Keys, Where, Does).
QWidget* showKeyboardShortcuts(QWidget* parent);

}  // namespace ffdkit::app
