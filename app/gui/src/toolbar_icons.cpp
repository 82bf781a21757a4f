#include "toolbar_icons.h"

#include <array>
#include <stdexcept>
#include <string>

#include <QAction>
#include <QIcon>
#include <QMenu>
#include <QPixmap>
#include <QSettings>
#include <QToolBar>
#include <QtGlobal>

namespace ffdkit::app {

namespace {
constexpr std::array kIcons{
    ActionIcon{"actionUndo", "undo", "Undo"},
    ActionIcon{"actionRedo", "redo", "Redo"},
    ActionIcon{"actionAddPrimitive", "add-primitive", "Primitive"},
    ActionIcon{"actionNewLattice", "new-lattice", "Lattice"},
    ActionIcon{"actionAddTranslate", "add-translate", "Translate"},
    ActionIcon{"actionAddRotate", "add-rotate", "Rotate"},
    ActionIcon{"actionAddScale", "add-scale", "Scale"},
    ActionIcon{"actionBind", "bind", "Bind"},
    ActionIcon{"actionAttach", "attach", "Attach"},
    ActionIcon{"actionDirectManipulation", "direct-manipulation", "Direct"},
    ActionIcon{"actionEditMode", "edit-lattice", "Edit Points"},
};

void applyToolbarStyle(QToolBar* toolbar, bool textUnderIcons) {
  toolbar->setToolButtonStyle(textUnderIcons ? Qt::ToolButtonTextUnderIcon : Qt::ToolButtonIconOnly);
}
}  // namespace

std::span<const ActionIcon> actionIcons() { return kIcons; }

void applyActionIcons(QObject* root) {
  bool drawable = true;
  for (const ActionIcon& row : kIcons) {
    auto* action = root->findChild<QAction*>(QString::fromLatin1(row.action));
    if (action == nullptr) throw std::logic_error(std::string("toolbar icon ") + row.icon + ": no action '" + row.action + "'");
    const QIcon icon(QStringLiteral(":/icons/%1.svg").arg(QString::fromLatin1(row.icon)));
    drawable = drawable && !icon.pixmap(16, 16).isNull();
    action->setIcon(icon);
    action->setIconText(QObject::tr(row.shortName));
  }
  static bool warned = false;
  if (!drawable && !warned) {
    warned = true;
    qWarning("ffdkit: Qt cannot draw the toolbar's SVG icons (install Qt's SVG module, libqt6svg6)");
  }
}

QAction* addToolbarTextOption(QMenu* menu, QToolBar* toolbar) {
  QAction* option = menu->addAction(QObject::tr("Toolbar &Text Under Icons"));
  option->setObjectName("actionToolbarTextUnderIcons");
  option->setCheckable(true);
  option->setChecked(QSettings().value(kToolbarTextUnderIconsKey, false).toBool());
  applyToolbarStyle(toolbar, option->isChecked());
  QObject::connect(option, &QAction::toggled, toolbar, [toolbar](bool on) {
    QSettings().setValue(kToolbarTextUnderIconsKey, on);
    applyToolbarStyle(toolbar, on);
  });
  return option;
}

}  // namespace ffdkit::app
