#include "keyboard_shortcuts.h"

#include <array>
#include <stdexcept>

#include <QAction>
#include <QDialog>
#include <QHeaderView>
#include <QKeyEvent>
#include <QSet>
#include <QStringList>
#include <QTableWidget>
#include <QVBoxLayout>

namespace ffdkit::app {

namespace {

using C = ShortcutContext;

// The table. Keys of menu actions are set from here only (applyKeyboardShortcuts); keys the view
// handles itself are checked against it (matchesShortcut).
constexpr std::array kShortcuts{
    KeyboardShortcut{"Ctrl+N", "actionNewScene", C::Window, "New scene"},
    KeyboardShortcut{"Ctrl+O", "actionOpenScene", C::Window, "Open a scene"},
    KeyboardShortcut{"Ctrl+S", "actionSaveScene", C::Window, "Save the scene"},
    KeyboardShortcut{"Ctrl+Shift+S", "actionSaveSceneAs", C::Window, "Save the scene under another name"},
    KeyboardShortcut{"Ctrl+Q", "actionQuit", C::Window, "Quit (asks to save changes)"},
    KeyboardShortcut{"Ctrl+Z", "actionUndo", C::Window, "Undo"},
    KeyboardShortcut{"Ctrl+Shift+Z", "actionRedo", C::Window, "Redo"},
    KeyboardShortcut{"Del", "actionRemove", C::Window, "Delete the selected widget, binding or objects"},
    KeyboardShortcut{"F2", "actionRename", C::Window, "Rename the selected object or widget"},
    KeyboardShortcut{"D", "actionDirectManipulation", C::Window, "Direct manipulation on / off"},
    KeyboardShortcut{"I", "actionInsertKey", C::Window, "Insert a key for the selection at the current frame"},
    KeyboardShortcut{"Alt+I", "actionDeleteKey", C::Window, "Delete the selection's keys at the current frame"},
    KeyboardShortcut{"Space", "actionPlayPause", C::Window, "Play / pause the animation at the scene's frame rate"},
    KeyboardShortcut{"Alt+Left", "actionPreviousKey", C::Window, "Jump to the previous key"},
    KeyboardShortcut{"Alt+Right", "actionNextKey", C::Window, "Jump to the next key"},
    KeyboardShortcut{"Alt+D", "actionClearPins", C::Window, "Clear the pinned object points of direct manipulation"},
    KeyboardShortcut{"F", "actionFrameSelected", C::View, "Frame the selection (everything when nothing is selected)"},
    KeyboardShortcut{"Num+.", "actionFrameSelected", C::View, "Frame the selection"},
    KeyboardShortcut{"Home", "actionFrameAll", C::View, "Frame everything"},
    KeyboardShortcut{"Num+1", "actionViewFront", C::View, "Front view (looking along +y, z up)"},
    KeyboardShortcut{"Ctrl+Num+1", "actionViewBack", C::View, "Back view (looking along -y)"},
    KeyboardShortcut{"Num+3", "actionViewRight", C::View, "Right view (looking along -x, z up)"},
    KeyboardShortcut{"Ctrl+Num+3", "actionViewLeft", C::View, "Left view (looking along +x)"},
    KeyboardShortcut{"Num+7", "actionViewTop", C::View, "Top view (looking down -z, y up)"},
    KeyboardShortcut{"Ctrl+Num+7", "actionViewBottom", C::View, "Bottom view (looking up +z)"},
    KeyboardShortcut{"Num+5", "actionOrthographic", C::View, "Orthographic / perspective projection"},
    KeyboardShortcut{"F1", "actionKeyboardShortcuts", C::Window, "This list of keyboard shortcuts"},
    KeyboardShortcut{"Esc", "cancelDrag", C::Drag,
                     "Cancel the drag, or the move / turn / size (G / R / S): the scene goes back to where it started"},
    KeyboardShortcut{"Tab", "actionEditMode", C::View, "Edit the selected lattice's points on / off"},
    KeyboardShortcut{"A", "actionSelectAll", C::EditMode, "Select every point"},
    KeyboardShortcut{"Alt+A", "actionSelectNone", C::EditMode, "Select no point"},
    KeyboardShortcut{"Ctrl+I", "actionSelectInvert", C::EditMode, "Invert the selection"},
    KeyboardShortcut{"B", "actionBoxSelect", C::EditMode, "Box select: the next drag's rectangle selects (even from a point)"},
    KeyboardShortcut{"G", "actionMoveSelection", C::EditMode,
                     "Move the selected points (or two or more selected widgets) with the pointer; click or Enter confirms"},
    KeyboardShortcut{"R", "actionRotateSelection", C::EditMode, "Turn the selection about the pivot"},
    KeyboardShortcut{"S", "actionScaleSelection", C::EditMode, "Size the selection about the pivot"},
    KeyboardShortcut{"O", "actionSoftSelection", C::EditMode,
                     "Soft selection on / off: G / R / S also move the points near the selection, by the falloff"},
    KeyboardShortcut{"Alt+O", "actionSoftConnected", C::EditMode,
                     "Soft selection along the lattice's grid lines only (connected only) on / off"},
    KeyboardShortcut{"Ctrl+M", "actionMakeCell", C::EditMode, "Make a cell of the selected points (point, edge, face, slab, box; else asks: custom)"},
    KeyboardShortcut{"X", "constrainAxisX", C::Drag, "During G / R / S: along (about) x only; again: free"},
    KeyboardShortcut{"Y", "constrainAxisY", C::Drag, "During G / R / S: along (about) y only; again: free"},
    KeyboardShortcut{"Z", "constrainAxisZ", C::Drag, "During G / R / S: along (about) z only; again: free"},
    KeyboardShortcut{"Shift+X", "excludeAxisX", C::Drag, "During G / S: in the yz plane (x excluded)"},
    KeyboardShortcut{"Shift+Y", "excludeAxisY", C::Drag, "During G / S: in the xz plane (y excluded)"},
    KeyboardShortcut{"Shift+Z", "excludeAxisZ", C::Drag, "During G / S: in the xy plane (z excluded)"},
    KeyboardShortcut{"Return", "confirmTransform", C::Drag, "Confirm G / R / S, or a drag with a typed value (one undo step)"},
    KeyboardShortcut{"Backspace", "typedBackspace", C::Drag, "Remove the last typed character of a value"},
    KeyboardShortcut{"PgUp", "softRadiusUp", C::Drag,
                     "During G / R / S with soft selection: a larger radius (the wheel towards you too)"},
    KeyboardShortcut{"PgDown", "softRadiusDown", C::Drag,
                     "During G / R / S with soft selection: a smaller radius (the wheel away from you too)"},
};

bool isAction(const KeyboardShortcut& s) { return std::string_view(s.action).starts_with("action"); }

QKeySequence keysOf(const KeyboardShortcut& s) { return QKeySequence(QString::fromLatin1(s.keys), QKeySequence::PortableText); }

}  // namespace

std::span<const KeyboardShortcut> keyboardShortcuts() { return kShortcuts; }

QList<QKeySequence> shortcutsOf(std::string_view action) {
  QList<QKeySequence> keys;
  for (const KeyboardShortcut& s : kShortcuts)
    if (action == s.action) keys.push_back(keysOf(s));
  return keys;
}

bool matchesShortcut(const QKeyEvent& event, std::string_view action) {
  for (const KeyboardShortcut& s : kShortcuts) {
    if (action != s.action) continue;
    const QKeySequence keys = keysOf(s);
    if (keys.count() != 1) continue;
    Qt::KeyboardModifiers modifiers = event.modifiers();
    if (!keys[0].keyboardModifiers().testFlag(Qt::KeypadModifier)) modifiers &= ~Qt::KeypadModifier;
    if (keys[0] == QKeyCombination(modifiers, static_cast<Qt::Key>(event.key()))) return true;
  }
  return false;
}

void applyKeyboardShortcuts(QObject* root) {
  QSet<QAction*> tipped;  // an action with several rows gets its keys in its tooltip once
  for (const KeyboardShortcut& s : kShortcuts) {
    if (!isAction(s)) continue;
    auto* action = root->findChild<QAction*>(QString::fromLatin1(s.action));
    if (action == nullptr)
      throw std::logic_error(std::string("keyboard shortcut ") + s.keys + ": no action '" + s.action + "'");
    action->setShortcuts(shortcutsOf(s.action));
    if (!tipped.contains(action)) action->setToolTip(withShortcutText(action->toolTip(), s.action));
    tipped.insert(action);
  }
}

QString withShortcutText(const QString& tip, std::string_view action) {
  QStringList keys;
  for (const KeyboardShortcut& s : kShortcuts)
    if (action == s.action) keys << shortcutKeysText(s);
  return keys.isEmpty() ? tip : tip + " (" + keys.join(", ") + ")";
}

QString shortcutKeysText(const KeyboardShortcut& shortcut) {
  QString text = QString::fromLatin1(shortcut.keys);
  text.replace("Num+", "Numpad ");
  return text;
}

QString shortcutContextText(ShortcutContext context) {
  switch (context) {
    case ShortcutContext::Window: return QObject::tr("anywhere");
    case ShortcutContext::View: return QObject::tr("3D view");
    case ShortcutContext::Drag: return QObject::tr("while dragging");
    case ShortcutContext::EditMode: return QObject::tr("lattice edit mode");
  }
  return {};
}

std::string shortcutMarkdownRow(const KeyboardShortcut& shortcut) {
  return "| " + shortcutKeysText(shortcut).toStdString() + " | " + shortcutContextText(shortcut.context).toStdString() +
         " | " + shortcut.description + " |";
}

QWidget* showKeyboardShortcuts(QWidget* parent) {
  auto* dialog = parent->findChild<QDialog*>("keyboardShortcutsDialog");
  if (dialog == nullptr) {
    dialog = new QDialog(parent);
    dialog->setObjectName("keyboardShortcutsDialog");
    dialog->setWindowTitle(QObject::tr("Keyboard Shortcuts"));
    auto* table = new QTableWidget(static_cast<int>(kShortcuts.size()), 3);
    table->setObjectName("shortcutsTable");
    table->setHorizontalHeaderLabels({QObject::tr("Keys"), QObject::tr("Where"), QObject::tr("Does")});
    table->verticalHeader()->hide();
    table->setEditTriggers(QAbstractItemView::NoEditTriggers);
    for (int row = 0; row < static_cast<int>(kShortcuts.size()); ++row) {
      const KeyboardShortcut& s = kShortcuts[static_cast<std::size_t>(row)];
      table->setItem(row, 0, new QTableWidgetItem(shortcutKeysText(s)));
      table->setItem(row, 1, new QTableWidgetItem(shortcutContextText(s.context)));
      table->setItem(row, 2, new QTableWidgetItem(QObject::tr(s.description)));
    }
    table->resizeColumnsToContents();
    table->horizontalHeader()->setStretchLastSection(true);
    auto* layout = new QVBoxLayout(dialog);
    layout->addWidget(table);
    dialog->resize(640, 480);
  }
  dialog->show();
  dialog->raise();
  return dialog;
}

}  // namespace ffdkit::app
