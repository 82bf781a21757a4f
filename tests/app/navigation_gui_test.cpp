// Navigating the 3D view in the real window (Xvfb, real Qt mouse and key events): a drag on
// empty space is a turntable orbit (no roll; trackball as a remembered preference), F / numpad .
// frame the selection, Home frames all, numpad 1 / 3 / 7 (Ctrl: the opposite) look along the
// axes, numpad 5 toggles orthographic; a dropped mesh is framed; a Y-up OBJ file imported with
// File > Import Up Axis > Y Up stands up.
#include <QAction>
#include <QMimeData>
#include <QSettings>
#include <QUrl>

#include <filesystem>

#include <vtkCamera.h>
#include <vtkRenderer.h>

#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/scenes/mesh_io.h"
#include "gui_test_support.h"

using namespace ffdkit;
using namespace ffdkit::app::testing;
using app::MainWindow;

namespace {

const std::filesystem::path kColumn = FFDKIT_SOURCE_DIR "/tests/data/y_up_column.obj";

Eigen::Vector3d dirOf(const scenes::Camera& c) { return (c.focalPoint - c.position).normalized(); }
Eigen::Vector3d rightOf(const scenes::Camera& c) { return dirOf(c).cross(c.viewUp).normalized(); }

// A left-button drag through `path` (pixels), one move per corner in ten steps each.
void dragAlong(MainWindow& w, const std::vector<QPoint>& path) {
  sendMouse(w.view(), QEvent::MouseButtonPress, path.front(), Qt::LeftButton, Qt::LeftButton);
  for (std::size_t i = 1; i < path.size(); ++i)
    for (int step = 1; step <= 10; ++step)
      sendMouse(w.view(), QEvent::MouseMove, path[i - 1] + (path[i] - path[i - 1]) * step / 10, Qt::NoButton,
                Qt::LeftButton);
  sendMouse(w.view(), QEvent::MouseButtonRelease, path.back(), Qt::LeftButton, Qt::NoButton);
}

// The points as drawn lie inside the view, and their extent fills at least `fill` of the view's
// smaller side.
void expectFramed(MainWindow& w, const Eigen::MatrixX3d& points, double fill) {
  w.view()->grabFramebuffer();
  const QSize size = w.view()->size();
  int left = size.width(), right = 0, top = size.height(), bottom = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const QPoint p = toWidget(w, points.row(i).transpose());
    QVERIFY2(p.x() >= 0 && p.x() < size.width() && p.y() >= 0 && p.y() < size.height(),
             qPrintable(QString("point %1 drawn at %2,%3, outside the %4x%5 view")
                            .arg(i).arg(p.x()).arg(p.y()).arg(size.width()).arg(size.height())));
    left = std::min(left, p.x());
    right = std::max(right, p.x());
    top = std::min(top, p.y());
    bottom = std::max(bottom, p.y());
  }
  const double extent = std::max(right - left, bottom - top);
  QVERIFY2(extent >= fill * std::min(size.width(), size.height()),
           qPrintable(QString("spans %1 px of %2").arg(extent).arg(std::min(size.width(), size.height()))));
}

// Drops files on the window as a file manager does (drag enter, then drop).
void dropFile(MainWindow& w, const std::filesystem::path& file) {
  QMimeData data;
  data.setUrls({QUrl::fromLocalFile(QString::fromStdString(file.string()))});
  const QPoint at = w.rect().center();
  QDragEnterEvent enter(at, Qt::CopyAction, &data, Qt::LeftButton, Qt::NoModifier);
  QApplication::sendEvent(&w, &enter);
  QDropEvent drop(at, Qt::CopyAction, &data, Qt::LeftButton, Qt::NoModifier);
  QApplication::sendEvent(&w, &drop);
}

}  // namespace

class NavigationGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    window_ = startWindow(QSize(1100, 760), StartSettings::Cleared);
    QVERIFY(window_ != nullptr);
  }
  void cleanup() { window_.reset(); }

  void aDragOnEmptySpaceIsATurntableOrbit() {
    MainWindow& w = *window_;
    w.openScene(kExamples / "default");
    const scenes::Camera start = w.sceneView().camera();
    // A closed square path, which leaves a trackball rolled.
    const std::vector<QPoint> square{{40, 40}, {240, 40}, {240, 240}, {40, 240}, {40, 40}};
    dragAlong(w, square);
    const scenes::Camera turned = w.sceneView().camera();
    QVERIFY((turned.position - start.position).norm() > 1e-3);
    QVERIFY2(std::abs(rightOf(turned).z()) < 1e-9, qPrintable(QString("rolled: right.z %1").arg(rightOf(turned).z())));
    QVERIFY(turned.viewUp.z() > 0.0);
    QVERIFY(std::abs((turned.position - turned.focalPoint).norm() - (start.position - start.focalPoint).norm()) < 1e-9);
    QCOMPARE(w.commands().position(), std::size_t{0});  // navigation is no edit

    // Trackball, a preference kept between sessions: the same path rolls the view.
    QAction* trackball = action(w, "actionTrackballOrbit");
    QVERIFY(!trackball->isChecked());
    trackball->trigger();
    QCOMPARE(QSettings().value("orbitStyle").toString(), QString("trackball"));
    w.sceneView().applyCamera(start);
    dragAlong(w, square);
    QVERIFY(std::abs(rightOf(w.sceneView().camera()).z()) > 0.01);
    window_.reset();
    window_ = openWindow(QSize(1100, 760));
    QVERIFY(action(*window_, "actionTrackballOrbit")->isChecked());
  }

  void fFramesTheSelectionAndHomeFramesAll() {
    MainWindow& w = *window_;
    w.openScene(kExamples / "default");
    // Look from far away and off to a side first.
    scenes::Camera away = w.sceneView().camera();
    away.position = away.focalPoint + 12.0 * (away.position - away.focalPoint) + Eigen::Vector3d(3.0, 0.0, 0.0);
    w.sceneView().applyCamera(away);
    clickRow(w, "pull");  // the default scene's arrow
    QCOMPARE(w.controller().selection().size(), std::size_t{1});
    pressKey(w, Qt::Key_F);
    const widgets::WidgetFrame arrow = w.scene().widgets.affineFrame(w.controller().selection().front());
    Eigen::MatrixX3d glyph(8, 3);  // the box frame() was given: the arrow's origin +- its size
    for (int c = 0; c < 8; ++c)
      for (int a = 0; a < 3; ++a) glyph(c, a) = arrow.frame.translation()(a) + ((c >> a) & 1 ? arrow.size : -arrow.size);
    expectFramed(w, glyph, 0.4);
    QVERIFY((w.sceneView().camera().focalPoint - arrow.frame.translation()).norm() < 1e-9);

    // Numpad . does the same; Home shows everything: the sphere and the lattice.
    w.sceneView().applyCamera(away);
    pressKey(w, Qt::Key_Period, Qt::KeypadModifier);
    QVERIFY((w.sceneView().camera().focalPoint - arrow.frame.translation()).norm() < 1e-9);
    pressKey(w, Qt::Key_Home);
    const widgets::WidgetId lattice = w.scene().widgets.find("lattice");
    expectFramed(w, w.deformer().points("sphere"), 0.3);
    expectFramed(w, w.scene().widgets.worldControlPoints(lattice), 0.3);
  }

  void numpadViewsLookAlongTheAxesAndFiveTogglesOrthographic() {
    MainWindow& w = *window_;
    w.openScene(kExamples / "default");
    const Eigen::Vector3d focal = w.sceneView().camera().focalPoint;
    struct Case {
      Qt::Key key;
      Qt::KeyboardModifiers modifiers;
      Eigen::Vector3d dir, up;
    };
    const Qt::KeyboardModifiers pad = Qt::KeypadModifier, ctrlPad = Qt::KeypadModifier | Qt::ControlModifier;
    for (const Case& c : {Case{Qt::Key_1, pad, {0, 1, 0}, {0, 0, 1}}, Case{Qt::Key_1, ctrlPad, {0, -1, 0}, {0, 0, 1}},
                          Case{Qt::Key_3, pad, {-1, 0, 0}, {0, 0, 1}}, Case{Qt::Key_3, ctrlPad, {1, 0, 0}, {0, 0, 1}},
                          Case{Qt::Key_7, pad, {0, 0, -1}, {0, 1, 0}}, Case{Qt::Key_7, ctrlPad, {0, 0, 1}, {0, -1, 0}}}) {
      pressKey(w, c.key, c.modifiers);
      const scenes::Camera camera = w.sceneView().camera();
      const QString what = QKeySequence(c.modifiers | c.key).toString();
      QVERIFY2((dirOf(camera) - c.dir).norm() < 1e-12, qPrintable(what));
      QVERIFY2((camera.viewUp - c.up).norm() < 1e-12, qPrintable(what));
      QVERIFY2((camera.focalPoint - focal).norm() < 1e-12, qPrintable(what));
    }
    vtkCamera* vtk = w.view()->renderer()->GetActiveCamera();
    QCOMPARE(vtk->GetParallelProjection(), 0);
    const double distance = vtk->GetDistance();
    pressKey(w, Qt::Key_5, Qt::KeypadModifier);
    QCOMPARE(vtk->GetParallelProjection(), 1);
    QVERIFY(action(w, "actionOrthographic")->isChecked());
    QVERIFY(std::abs(vtk->GetParallelScale() - distance * std::tan(vtk->GetViewAngle() * std::numbers::pi / 360.0)) < 1e-9);
    // Picking still works in parallel: the arrow's pick tolerance follows the parallel scale.
    QVERIFY(std::abs(w.sceneView().pixelSize() - 2.0 * vtk->GetParallelScale() / w.view()->height()) < 1e-9);
    pressKey(w, Qt::Key_5, Qt::KeypadModifier);
    QCOMPARE(vtk->GetParallelProjection(), 0);
    QVERIFY(!action(w, "actionOrthographic")->isChecked());
    // The top-row 5 is not the keypad's.
    pressKey(w, Qt::Key_5);
    QCOMPARE(vtk->GetParallelProjection(), 0);
  }

  void anImportedMeshIsFramedAndAYUpFileStandsUp() {
    MainWindow& w = *window_;
    // Z up (the default): the file's coordinates as written; the import frames the object.
    QVERIFY(action(w, "actionImportZUp")->isChecked());
    dropFile(w, kColumn);
    QCOMPARE(w.scene().objects().size(), std::size_t{1});
    const scenes::MeshData file = scenes::readMesh(kColumn);
    QCOMPARE(w.scene().objects()[0].mesh.points, file.points);
    expectFramed(w, w.deformer().points("y_up_column"), 0.4);

    // Y up: turned once as it is read; it stands on z = 0, 3 tall, its front (+z in the file)
    // toward -y.
    action(w, "actionImportYUp")->trigger();
    QCOMPARE(QSettings().value("importUpAxis").toString(), QString("y"));
    dropFile(w, kColumn);
    QCOMPARE(w.scene().objects().size(), std::size_t{2});
    const scenes::SceneObject& column = w.scene().objects()[1];
    QCOMPARE(column.name, std::string("y_up_column2"));
    for (Eigen::Index i = 0; i < file.points.rows(); ++i) {
      QCOMPARE(column.mesh.points(i, 0), file.points(i, 0));
      QCOMPARE(column.mesh.points(i, 1), -file.points(i, 2));
      QCOMPARE(column.mesh.points(i, 2), file.points(i, 1));
    }
    QCOMPARE(column.mesh.points.col(2).minCoeff(), 0.0);
    QCOMPARE(column.mesh.points.col(2).maxCoeff(), 3.0);
    QCOMPARE(column.mesh.points.col(1).maxCoeff(), -0.1);
    expectFramed(w, w.deformer().points("y_up_column2"), 0.4);
    // Undo removes it; the choice is remembered by the next window.
    action(w, "actionUndo")->trigger();
    QCOMPARE(w.scene().objects().size(), std::size_t{1});
    window_.reset();
    window_ = openWindow(QSize(1100, 760));
    QVERIFY(action(*window_, "actionImportYUp")->isChecked());
  }

 private:
  std::unique_ptr<MainWindow> window_;
};

int main(int argc, char** argv) { return runGuiTest<NavigationGuiTest>(argc, argv); }

#include "navigation_gui_test.moc"
