#include "read_preferences.h"

#include <stdexcept>
#include <utility>

#include <QAction>
#include <QDialogButtonBox>
#include <QFormLayout>
#include <QLabel>
#include <QLineEdit>
#include <QMenu>
#include <QPushButton>
#include <QSettings>

namespace ffdkit::app {

namespace {

/// The key the opt-out was kept under when it applied to mesh files only.
constexpr const char* kOldAllowOutsideMeshesKey = "allowMeshesOutsideSceneFolder";
/// What the app names where the library's messages name the CLI's options.
constexpr const char* kLimitsItem = "(File > Read Limits...)";
constexpr const char* kAllowOutsideItem = "File > Allow Files Outside a Scene's Folder";

std::uint64_t storedLimit(const char* key, std::uint64_t fallback) {
  bool ok = false;
  const qulonglong value = QSettings().value(key).toULongLong(&ok);
  return ok && value > 0 ? value : fallback;
}

QString qs(const std::string& text) { return QString::fromStdString(text); }

/// The limit as the dialog shows it: exact, in the largest binary unit that divides it.
QString byteSizeField(std::uint64_t bytes) {
  const char* units[] = {"", "K", "M", "G", "T"};
  int unit = 0;
  while (unit < 4 && bytes % 1024 == 0) {
    bytes /= 1024;
    ++unit;
  }
  return QString::number(bytes) + units[unit];
}

QString countField(std::uint64_t count) {
  const char* units[] = {"", "k", "M", "G"};
  int unit = 0;
  while (unit < 3 && count % 1000 == 0) {
    count /= 1000;
    ++unit;
  }
  return QString::number(count) + units[unit];
}

}  // namespace

meshio::ReadLimits readLimits() {
  const meshio::ReadLimits defaults;
  meshio::ReadLimits limits;
  limits.maxMemoryBytes = storedLimit(kMaxMemoryKey, defaults.maxMemoryBytes);
  limits.maxPoints = storedLimit(kMaxPointsKey, defaults.maxPoints);
  return limits;
}

void setReadLimits(const meshio::ReadLimits& limits) {
  QSettings settings;
  settings.setValue(kMaxMemoryKey, qulonglong(limits.maxMemoryBytes));
  settings.setValue(kMaxPointsKey, qulonglong(limits.maxPoints));
}

meshio::PathConfinement pathConfinement() {
  QSettings settings;
  meshio::PathConfinement confinement;
  confinement.allowOutside = settings.contains(kAllowOutsideKey) ? settings.value(kAllowOutsideKey).toBool()
                                                                 : settings.value(kOldAllowOutsideMeshesKey, false).toBool();
  return confinement;
}

scenes::SceneReadOptions sceneReadOptions() {
  scenes::SceneReadOptions options;
  options.confinement = pathConfinement();
  options.limits = readLimits();
  return options;
}

meshio::MeshReadOptions meshReadOptions() {
  meshio::MeshReadOptions options;
  options.confinement = pathConfinement();
  options.limits = readLimits();
  return options;
}

scenes::WidgetReadOptions widgetReadOptions() {
  scenes::WidgetReadOptions options;
  options.limits = readLimits();
  return options;
}

std::string readErrorText(const std::string& what) {
  const std::pair<std::string, std::string> replacements[] = {
      {"(--max-memory)", kLimitsItem},
      {"(--max-points)", kLimitsItem},
      {"--allow-outside-meshes or the app's preference", kAllowOutsideItem},
      {"--allow-outside or the app's preference", kAllowOutsideItem},
  };
  std::string text = what;
  for (const auto& [cli, app] : replacements)
    for (std::size_t at = text.find(cli); at != std::string::npos; at = text.find(cli, at + app.size()))
      text.replace(at, cli.size(), app);
  return text;
}

ReadLimitsDialog::ReadLimitsDialog(QWidget* parent) : QDialog(parent) {
  setObjectName("readLimitsDialog");
  setWindowTitle(tr("Read Limits"));
  const meshio::ReadLimits limits = readLimits();
  maxMemory_ = new QLineEdit(byteSizeField(limits.maxMemoryBytes), this);
  maxMemory_->setObjectName("maxMemory");
  maxMemory_->setToolTip(tr("What one read (a scene with all its meshes, a mesh, a widget file) may allocate: "
                            "a number with K, M, G or T (powers of 1024), e.g. 512M, 8G"));
  maxPoints_ = new QLineEdit(countField(limits.maxPoints), this);
  maxPoints_->setObjectName("maxPoints");
  maxPoints_->setToolTip(tr("Points one read may produce: a number with k, M or G (powers of 1000), e.g. 2M"));
  problem_ = new QLabel(this);
  problem_->setObjectName("problem");
  problem_->setWordWrap(true);
  problem_->hide();
  auto* form = new QFormLayout(this);
  auto* intro = new QLabel(tr("A file that would need more is refused with a message, before anything is allocated."), this);
  intro->setWordWrap(true);
  form->addRow(intro);
  form->addRow(tr("Memory per read"), maxMemory_);
  form->addRow(tr("Points per read"), maxPoints_);
  form->addRow(problem_);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel | QDialogButtonBox::RestoreDefaults);
  buttons->button(QDialogButtonBox::RestoreDefaults)->setObjectName("defaults");
  connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  connect(buttons->button(QDialogButtonBox::RestoreDefaults), &QPushButton::clicked, this, [this] {
    const meshio::ReadLimits defaults;
    maxMemory_->setText(byteSizeField(defaults.maxMemoryBytes));
    maxPoints_->setText(countField(defaults.maxPoints));
  });
  form->addRow(buttons);
}

void ReadLimitsDialog::accept() {
  meshio::ReadLimits limits;
  try {
    limits.maxMemoryBytes = meshio::parseByteSize(maxMemory_->text().trimmed().toStdString());
    limits.maxPoints = meshio::parseCount(maxPoints_->text().trimmed().toStdString());
  } catch (const std::invalid_argument& e) {
    problem_->setText(qs(e.what()));
    problem_->show();
    return;
  }
  setReadLimits(limits);
  QDialog::accept();
}

void addReadPreferenceActions(QMenu* file, QWidget* dialogParent) {
  // Off by default: a shared file must not make the app read files outside its folder
  // (meshio/path_confinement.h).
  QAction* outside = file->addAction(QObject::tr("Allow Files &Outside a Scene's Folder"));
  outside->setObjectName("actionAllowOutside");
  outside->setToolTip(QObject::tr("Let a file open other files it names outside its own folder: a scene's meshes "
                                  "and widget file, a glTF's buffers"));
  outside->setCheckable(true);
  outside->setChecked(pathConfinement().allowOutside);
  QObject::connect(outside, &QAction::toggled, file, [](bool on) { QSettings().setValue(kAllowOutsideKey, on); });
  QAction* limits = file->addAction(QObject::tr("Read &Limits..."));
  limits->setObjectName("actionReadLimits");
  QObject::connect(limits, &QAction::triggered, dialogParent, [dialogParent] {
    ReadLimitsDialog dialog(dialogParent);
    dialog.exec();
  });
}

}  // namespace ffdkit::app
