#include "ffdkit/app/main_window.h"

#include <QAction>
#include <QFileDialog>
#include <QMenuBar>
#include <QMessageBox>
#include <QStatusBar>

#include "ffdkit/app/scene_view.h"
#include "ffdkit/app/vtk_view_widget.h"
#include "ffdkit/scenes/scene_file.h"

namespace ffdkit::app {

struct MainWindow::Impl {
  VtkViewWidget* view = nullptr;
  std::unique_ptr<SceneView> sceneView;
  scenes::Scene scene;
  scenes::SceneDeformer deformer;
};

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent), impl_(std::make_unique<Impl>()) {
  setWindowTitle("ffdkit");
  impl_->view = new VtkViewWidget(this);
  setCentralWidget(impl_->view);
  impl_->sceneView = std::make_unique<SceneView>(impl_->view->renderer());

  QMenu* file = menuBar()->addMenu(tr("&File"));
  QAction* open = file->addAction(tr("&Open Scene..."), this, &MainWindow::openSceneDialog);
  open->setShortcut(QKeySequence::Open);
  file->addSeparator();
  QAction* quit = file->addAction(tr("&Quit"), this, &QWidget::close);
  quit->setShortcut(QKeySequence::Quit);

  statusBar()->showMessage(tr("Ready"));
  resize(1024, 768);
}

MainWindow::~MainWindow() = default;

void MainWindow::openScene(const std::filesystem::path& path) {
  setScene(scenes::readScene(path));
  setWindowTitle(QString("ffdkit - %1").arg(QString::fromStdString(path.string())));
}

void MainWindow::setScene(scenes::Scene scene) {
  impl_->scene = std::move(scene);
  impl_->deformer.reset();
  impl_->deformer.update(impl_->scene);
  impl_->sceneView->show(impl_->scene, impl_->deformer);
  statusBar()->showMessage(tr("%1 objects, %2 lattices")
                               .arg(impl_->scene.objects.size())
                               .arg(impl_->scene.widgets.widgets(widgets::WidgetType::Lattice).size()));
  impl_->view->requestRender();
}

const scenes::Scene& MainWindow::scene() const { return impl_->scene; }

VtkViewWidget* MainWindow::view() const { return impl_->view; }

void MainWindow::openSceneDialog() {
  const QString path =
      QFileDialog::getOpenFileName(this, tr("Open Scene"), QString(), tr("ffdkit scenes (*.json);;All files (*)"));
  if (path.isEmpty()) return;
  try {
    openScene(path.toStdString());
  } catch (const std::exception& e) {
    QMessageBox::critical(this, tr("Cannot open scene"), QString::fromStdString(e.what()));
  }
}

}  // namespace ffdkit::app
