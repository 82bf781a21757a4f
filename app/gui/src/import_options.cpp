#include "import_options.h"

#include <QAction>
#include <QActionGroup>
#include <QMenu>
#include <QSettings>

namespace ffdkit::app {

void addImportUpAxisMenu(QMenu* file) {
  QMenu* menu = file->addMenu(QObject::tr("Import &Up Axis"));
  auto* group = new QActionGroup(menu);
  const scenes::UpAxis current = importUpAxis();
  for (const auto& [axis, text, name] :
       {std::tuple{scenes::UpAxis::Z, QObject::tr("&Z Up (as written)"), "actionImportZUp"},
        std::tuple{scenes::UpAxis::Y, QObject::tr("&Y Up (OBJ, glTF: turned to Z up)"), "actionImportYUp"}}) {
    QAction* a = menu->addAction(text);
    a->setObjectName(name);
    a->setCheckable(true);
    a->setChecked(axis == current);
    group->addAction(a);
    QObject::connect(a, &QAction::triggered, menu, [axis = axis] {
      const std::string_view value = scenes::upAxisName(axis);
      QSettings().setValue(kImportUpAxisKey, QString::fromLatin1(value.data(), static_cast<qsizetype>(value.size())));
    });
  }
}

scenes::UpAxis importUpAxis() {
  return QSettings().value(kImportUpAxisKey, "z").toString() == "y" ? scenes::UpAxis::Y : scenes::UpAxis::Z;
}

}  // namespace ffdkit::app
