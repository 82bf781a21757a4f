// MainWindow, the document's files: open, save, save as, new; the unsaved-changes prompt; the
// title and the recent files; autosave recovery; widget files, meshes; delete and rename.
#include <fstream>
#include <string>

#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QInputDialog>
#include <QMessageBox>
#include <QPushButton>
#include <QSettings>

#include "ffdkit/meshio/mesh_format.h"
#include "ffdkit/scenes/cad_objects.h"
#include "ffdkit/scenes/mesh_io.h"
#include "ffdkit/scenes/scene_file.h"
#include "ffdkit/scenes/volume_object.h"
#include "ffdkit/scenes/widget_file.h"
#include "ffdkit/interaction/scene_bounds.h"
#include "import_options.h"
#include "main_window_impl.h"
#include "read_preferences.h"

namespace ffdkit::app {

namespace window_detail {

bool isMeshFile(const std::filesystem::path& path) {
  return meshio::meshFormatOf(path).has_value() || scenes::isCadFile(path);  // a STEP or IGES part: its tessellation
}

// A widget file says "format": "ffdkit-widgets" near its top; a scene says "ffdkit-scene".
bool isWidgetFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string head(512, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  const auto widgetsAt = head.find("\"ffdkit-widgets\"");
  const auto sceneAt = head.find("\"ffdkit-scene\"");
  return widgetsAt != std::string::npos && (sceneAt == std::string::npos || widgetsAt < sceneAt);
}

// What openAny does with `path`: a scene replaces the document (so first ask to save it).
bool opensAsScene(const std::filesystem::path& path) {
  return !isMeshFile(path) && (std::filesystem::is_directory(path) || !isWidgetFile(path));
}

}  // namespace window_detail

using namespace window_detail;

void MainWindow::openScene(const std::filesystem::path& path) {
  setScene(scenes::readScene(path, sceneReadOptions()));
  setDocumentPath(std::filesystem::is_directory(path) ? path / "scene.json" : path);
}

void MainWindow::saveScene(const std::filesystem::path& path) {
  scenes::Scene copy = impl_->scene;
  copy.setCamera(impl_->sceneView->camera());
  copy.widgetFile.reset();
  // The reading rule for the paths the scene names: what is saved opens again.
  scenes::writeScene(path, copy, scenes::SceneWriteOptions{.confinement = pathConfinement()});
  impl_->commands.markClean();
  impl_->restoredUnsaved = false;
  setDocumentPath(path);
  impl_->autosave();  // nothing left to recover
  impl_->status->say(tr("Saved %1").arg(qs(path.string())), 5000);
}

void MainWindow::newScene() {
  setScene({});
  setDocumentPath({});
}

bool MainWindow::isModified() const { return impl_->modified(); }
std::filesystem::path MainWindow::documentPath() const { return impl_->scenePath; }
QString MainWindow::statusMessage() const { return impl_->status->message(); }

void MainWindow::setDocumentPath(const std::filesystem::path& path) {
  Impl& d = *impl_;
  d.scenePath = path;
  // The file's name; a sample scene's "scene.json" by its folder.
  QString name = tr("untitled");
  if (!path.empty()) {
    const QFileInfo info(qs(path.string()));
    name = info.fileName() == "scene.json" ? info.dir().dirName() + "/" + info.fileName() : info.fileName();
  }
  setWindowTitle(tr("%1[*] - ffdkit").arg(name));
  setWindowModified(d.modified());
  if (path.empty()) return;
  QSettings settings;
  QStringList recent = settings.value("recentFiles").toStringList();
  const QString entry = qs(path.string());
  recent.removeAll(entry);
  recent.prepend(entry);
  settings.setValue("recentFiles", recent.mid(0, kMaxRecent));
  rebuildRecentMenu();
}

void MainWindow::rebuildRecentMenu() {
  Impl& d = *impl_;
  d.recentMenu->clear();
  const QStringList recent = QSettings().value("recentFiles").toStringList();
  for (const QString& path : recent.mid(0, kMaxRecent)) {
    d.recentMenu->addAction(path, this, [this, path] {
      const std::filesystem::path file = path.toStdString();
      if (opensAsScene(file) && !maybeSave()) return;
      try {
        openAny(file);
      } catch (const std::exception& e) {
        QMessageBox::critical(this, tr("Cannot open"), qs(readErrorText(e.what())));
      }
    });
  }
  d.recentMenu->setEnabled(!recent.isEmpty());
}

bool MainWindow::saveInteractively(bool askForPath) {
  std::filesystem::path path = impl_->scenePath;
  if (askForPath || path.empty()) {
    const QString chosen =
        QFileDialog::getSaveFileName(this, tr("Save Scene As"), qs(path.string()), tr("ffdkit scenes (*.json)"));
    if (chosen.isEmpty()) return false;
    path = chosen.toStdString();
  }
  try {
    saveScene(path);
    return true;
  } catch (const std::exception& e) {
    // A scene is written beside its file and renamed over it only when whole (writeScene): a
    // failure (a full disk, too) leaves the file as it was.
    QMessageBox::critical(this, tr("Save Scene"),
                          tr("%1\n\nThe scene was not saved: the file on disk is as it was, and the edits are "
                             "still open.").arg(qs(e.what())));
    return false;
  }
}

bool MainWindow::maybeSave() {
  if (!impl_->modified()) return true;
  QMessageBox prompt(QMessageBox::Warning, tr("Unsaved changes"),
                     tr("%1 has unsaved changes.").arg(windowTitle().section("[*]", 0, 0)),
                     QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel, this);
  prompt.setObjectName("unsavedChangesPrompt");
  prompt.setInformativeText(tr("Save them before going on?"));
  prompt.setDefaultButton(QMessageBox::Save);
  switch (prompt.exec()) {
    case QMessageBox::Save: return saveInteractively(false);
    case QMessageBox::Discard: return true;
    default: return false;
  }
}

void MainWindow::startAutosaveTimer() {
  const int minutes = QSettings().value("autosaveMinutes", kDefaultAutosaveMinutes).toInt();
  if (minutes > 0) {
    impl_->autosaveTimer.start(minutes * 60 * 1000);
  } else {
    impl_->autosaveTimer.stop();  // still written on every change
  }
}

bool MainWindow::offerRecovery() {
  const std::vector<RecoveredDocument> found = RecoveryFile::orphans();
  if (found.empty()) return false;
  const RecoveredDocument& newest = found.front();
  const QString what = newest.origin.empty() ? tr("an untitled scene") : qs(newest.origin.string());
  QMessageBox prompt(QMessageBox::Question, tr("Recover unsaved changes"),
                     tr("ffdkit did not close properly. Restore the unsaved changes of %1?").arg(what),
                     QMessageBox::NoButton, this);
  prompt.setObjectName("recoveryPrompt");
  QPushButton* restore = prompt.addButton(tr("Restore"), QMessageBox::AcceptRole);
  prompt.addButton(tr("Discard"), QMessageBox::DestructiveRole);
  prompt.setDefaultButton(restore);
  prompt.exec();
  bool restored = false;
  if (prompt.clickedButton() == restore) {
    try {
      // The app's own recovery file: its mesh paths are the document's, wherever they lead;
      // the read limits hold as for any read.
      scenes::SceneReadOptions options = sceneReadOptions();
      options.confinement.allowOutside = true;
      setScene(scenes::readScene(newest.scene, options));
      impl_->restoredUnsaved = true;
      setDocumentPath(newest.origin);
      impl_->autosave();  // ours now: the next crash keeps it
      impl_->status->say(tr("Restored the unsaved changes of %1").arg(what));
      restored = true;
    } catch (const std::exception& e) {
      QMessageBox::critical(this, tr("Recover unsaved changes"), qs(readErrorText(e.what())));
      return false;  // the file stays for another try
    }
  }
  for (const RecoveredDocument& document : found) RecoveryFile::discard(document);
  return restored;
}

void MainWindow::deleteSelectedObjects() {
  Impl& d = *impl_;
  const std::vector<std::string> selected = d.selectedObjectNames();
  if (selected.empty()) throw std::invalid_argument("select an object to delete (in the outliner)");
  d.controller->removeObjects(selected);
  d.selectedObjects.clear();
  d.outliner->select(d.entries());
  d.properties->showSelection(d.entries());
}

void MainWindow::renameSelection() {
  Impl& d = *impl_;
  const auto widgets = d.controller->selection();
  const std::vector<std::string> selected = d.selectedObjectNames();
  const bool object = selected.size() == 1 && widgets.empty();
  if (!object && widgets.size() != 1)
    throw std::invalid_argument("select one object, lattice or widget to rename");
  const std::string old = object ? selected.front() : d.scene.widgets.name(widgets.front());
  QInputDialog dialog(this);
  dialog.setObjectName("renameDialog");
  dialog.setWindowTitle(tr("Rename"));
  dialog.setLabelText(tr("New name of '%1':").arg(qs(old)));
  dialog.setTextValue(qs(old));
  if (dialog.exec() != QDialog::Accepted) return;
  const std::string name = dialog.textValue().trimmed().toStdString();
  if (object) {
    d.controller->renameObject(old, name);  // the selection holds the object's id: it stays
  } else {
    d.controller->renameWidget(widgets.front(), name);
  }
  d.outliner->select(d.entries());
  d.properties->showSelection(d.entries());
}

void MainWindow::openWidgetFile(const std::filesystem::path& path) {
  Impl& d = *impl_;
  widgets::WidgetModel model = scenes::readWidgetFile(path, widgetReadOptions());
  // Its lattices go onto the selected object (or the only one), fitted as Attach fits them.
  std::optional<std::string> target;
  if (const std::vector<std::string> selected = d.selectedObjectNames(); !selected.empty()) {
    target = selected.front();
  } else if (d.scene.objects().size() == 1) {
    target = d.scene.objects().front().name;
  }
  if (model.roots().empty()) target.reset();
  d.controller->replaceWidgets(std::move(model), target);
  const QString file = QFileInfo(qs(path.string())).fileName();
  if (target) {
    d.status->say(tr("Opened widget file %1: its lattices deform '%2'").arg(file, qs(*target)));
  } else {
    d.status->say(tr("Opened widget file %1. Nothing is attached: select an object and a lattice, then "
                     "Widgets > Attach Lattice to Object").arg(file));
  }
}

void MainWindow::saveWidgetFile(const std::filesystem::path& path) {
  scenes::writeWidgetFile(path, impl_->scene.widgets);
  impl_->status->say(tr("Saved widget file %1").arg(qs(path.string())), 5000);
}

void MainWindow::importMesh(const std::filesystem::path& path) {
  scenes::SceneObject object;
  scenes::UpAxis up = importUpAxis();  // File > Import Up Axis
  if (scenes::isCadFile(path)) {
    up = scenes::UpAxis::Z;  // a CAD part keeps its axes: its exact export (cad_import.h) is in the file's frame
    meshio::ReadBudget budget(meshReadOptions().limits);
    object.mesh = scenes::readCadMesh(path, budget);
  } else {
    object.mesh = scenes::readMesh(path, meshReadOptions());
    scenes::convertToZUp(object.mesh, up);  // once, here; the scene file says "up" so a reload does it again
  }
  object.source = scenes::MeshFileSource{std::filesystem::absolute(path).string(), up};
  std::string base = path.stem().string();
  object.name = base;
  for (int n = 2; impl_->scene.findObject(object.name) != nullptr; ++n) object.name = base + std::to_string(n);
  const std::string name = object.name;
  impl_->controller->addObject(std::move(object));
  impl_->navigation->frameBox(selectionBounds(impl_->scene, impl_->deformed(), {}, {name}));  // show what came in
}

void MainWindow::exportMesh(const std::filesystem::path& path) {
  const auto& objects = impl_->scene.objects();
  if (objects.empty()) throw std::invalid_argument("the scene has no object to export");
  const std::vector<std::string> selected = impl_->selectedObjectNames();
  const std::string name = selected.empty() ? objects.front().name : selected.front();
  // A solver's volume mesh is written whole, in its own format, after its cells are checked
  // (volume_object.h); a surface format's extension (.obj, .ply, ...) writes its boundary surface.
  const scenes::SceneObject& object = *impl_->scene.findObject(name);
  const std::filesystem::path base = impl_->scenePath.empty() ? std::filesystem::path(".") : impl_->scenePath.parent_path();
  if (scenes::volumeMeshFormatOf(object.source, base) && !meshio::meshFormatOf(path)) {
    scenes::VolumeObjectWriteOptions options;
    options.confinement = pathConfinement();
    options.limits = meshReadOptions().limits;
    const scenes::VolumeObjectWriteResult result = scenes::writeVolumeObject(object, impl_->deformed().points(name), base, path, options);
    impl_->status->say(tr("Exported %1 to %2 (%3 mesh, %4 points; %5)")
                           .arg(qs(name), qs(path.string()), QString(meshio::volumeMeshFormatName(result.format)))
                           .arg(result.pointCount)
                           .arg(qs(result.quality.summary)),
                       5000);
    return;
  }
  scenes::MeshData mesh = object.mesh;
  mesh.points = impl_->deformed().points(name);
  scenes::writeMesh(path, mesh);
  impl_->status->say(tr("Exported %1 to %2").arg(qs(name), qs(path.string())), 5000);
}


void MainWindow::openAny(const std::filesystem::path& path) {
  if (isMeshFile(path)) {
    importMesh(path);
  } else if (!std::filesystem::is_directory(path) && isWidgetFile(path)) {
    openWidgetFile(path);
  } else {
    openScene(path);
  }
}

}  // namespace ffdkit::app
