// The operations toolbar's look: each action's icon (SVG files in app/gui/icons, compiled in
// as Qt resources under :/icons/) and the option to show the actions' names under the icons.
#pragma once

#include <span>

class QAction;
class QMenu;
class QObject;
class QToolBar;

namespace ffdkit::app {

/// One row: the QAction's object name, the icon file's name (without ".svg") and the short
/// name shown under the icon (QAction::iconText; the menu keeps the full text).
struct ActionIcon {
  const char* action;
  const char* icon;
  const char* shortName;
};

/// Every action that has an icon.
std::span<const ActionIcon> actionIcons();

/// Gives every action of the table below `root` its icon and short name.
/// @throws std::logic_error naming the row when its action is not found (a renamed action
///   cannot silently lose its icon). Warns once when Qt cannot draw SVG icons (its SVG icon
///   engine, Debian's libqt6svg6, missing): the toolbar then shows the actions' names.
void applyActionIcons(QObject* root);

/// The settings key of the toolbar option (a bool; false: icons only).
inline constexpr const char* kToolbarTextUnderIconsKey = "toolbarTextUnderIcons";

/// View > Toolbar Text Under Icons (object name "actionToolbarTextUnderIcons"): checkable,
/// kept in the user's settings, applied to `toolbar` now and on every change.
QAction* addToolbarTextOption(QMenu* menu, QToolBar* toolbar);

}  // namespace ffdkit::app
