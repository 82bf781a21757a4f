// The Qt 6 / VTK adapter under a real window: the default scene's pixels come out of the
// widget, and Qt mouse events reach VTK's interactor style.
#include <QApplication>
#include <QMouseEvent>
#include <QSurfaceFormat>
#include <QTest>

#include <cmath>
#include <cstdint>

#include <vtkCamera.h>
#include <vtkRenderer.h>

#include "ffdkit/gui/main_window.h"
#include "ffdkit/viewhost/vtk_view_widget.h"
#include "gui_test_support.h"

using ffdkit::app::MainWindow;

namespace {

// Mean colour of a (2r+1)^2 patch, as 0..255 floats.
QVector3D meanColour(const QImage& image, QPoint centre, int r) {
  QVector3D sum;
  int n = 0;
  for (int y = centre.y() - r; y <= centre.y() + r; ++y)
    for (int x = centre.x() - r; x <= centre.x() + r; ++x) {
      const QColor c = image.pixelColor(x, y);
      sum += QVector3D(c.red(), c.green(), c.blue());
      ++n;
    }
  return sum / float(n);
}

void sendMouse(QWidget* widget, QEvent::Type type, QPoint at, Qt::MouseButton button, Qt::MouseButtons buttons) {
  QMouseEvent event(type, QPointF(at), widget->mapToGlobal(QPointF(at)), button, buttons, Qt::NoModifier);
  QApplication::sendEvent(widget, &event);
}

}  // namespace

class VtkViewWidgetTest : public QObject {
  Q_OBJECT

 private slots:
  void rendersTheDefaultSceneThroughTheAdapter() {
    MainWindow window;
    window.openScene(FFDKIT_SOURCE_DIR "/scenes/examples/default");
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));

    const QImage image = window.view()->grabFramebuffer();
    QVERIFY(!image.isNull());
    QVERIFY(image.width() > 100 && image.height() > 100);

    // The sphere (orange, shaded) covers the middle of the view.
    const QVector3D middle = meanColour(image, QPoint(image.width() / 2, image.height() / 2), 3);
    QVERIFY2(middle.x() > middle.z() + 60.0f,
             qPrintable(QString("middle is not the sphere's orange: %1 %2 %3").arg(middle.x()).arg(middle.y()).arg(middle.z())));
    QVERIFY(middle.x() > 80.0f);

    // The corners show the scene's background colour.
    const auto& bg = window.scene().background();
    for (QPoint corner : {QPoint(4, 4), QPoint(image.width() - 5, image.height() - 5)}) {
      const QVector3D c = meanColour(image, corner, 2);
      QVERIFY2(std::abs(c.x() - 255.0 * bg.x()) < 3.0 && std::abs(c.y() - 255.0 * bg.y()) < 3.0 &&
                   std::abs(c.z() - 255.0 * bg.z()) < 3.0,
               qPrintable(QString("corner is not background: %1 %2 %3").arg(c.x()).arg(c.y()).arg(c.z())));
    }
  }

  void mouseDragThroughQtRotatesTheVtkCamera() {
    MainWindow window;
    window.openScene(FFDKIT_SOURCE_DIR "/scenes/examples/default");
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    window.view()->grabFramebuffer();  // a first frame, as a user would see before dragging

    vtkCamera* camera = window.view()->renderer()->GetActiveCamera();
    double before[3];
    camera->GetPosition(before);

    QWidget* view = window.view();
    const QPoint start(view->width() / 2, view->height() / 2);
    sendMouse(view, QEvent::MouseButtonPress, start, Qt::LeftButton, Qt::LeftButton);
    for (int step = 1; step <= 10; ++step)
      sendMouse(view, QEvent::MouseMove, start + QPoint(12 * step, 4 * step), Qt::NoButton, Qt::LeftButton);
    sendMouse(view, QEvent::MouseButtonRelease, start + QPoint(120, 40), Qt::LeftButton, Qt::NoButton);

    double after[3];
    camera->GetPosition(after);
    double focal[3];
    camera->GetFocalPoint(focal);
    // Trackball rotation keeps the distance to the focal point and turns the view direction.
    QVector3D b(before[0] - focal[0], before[1] - focal[1], before[2] - focal[2]);
    QVector3D a(after[0] - focal[0], after[1] - focal[1], after[2] - focal[2]);
    QVERIFY(std::abs(a.length() - b.length()) < 1e-3 * b.length());
    const double angle = std::acos(std::clamp(double(QVector3D::dotProduct(a.normalized(), b.normalized())), -1.0, 1.0));
    QVERIFY2(angle > 0.2, qPrintable(QString("camera turned only %1 rad").arg(angle)));

    // And the new view is what gets drawn: the frame after the drag differs from a fresh one.
    const QImage dragged = window.view()->grabFramebuffer();
    QVERIFY(!dragged.isNull());
  }

  // VTK's interactor style asks for a frame when a right (dolly) or middle (pan) gesture ends,
  // whether or not it moved the camera: a click that moved nothing draws no frame, a drag that
  // moved the camera draws one.
  void aClickThatMovesNoCameraDrawsNoFrame() {
    QWidget window;
    window.resize(400, 300);
    auto* view = new ffdkit::app::VtkViewWidget(&window);
    view->setGeometry(0, 0, 300, 200);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    view->grabFramebuffer();
    QApplication::processEvents();
    const std::uint64_t rendered = view->renders();
    const QPoint at(150, 100);
    for (Qt::MouseButton button : {Qt::RightButton, Qt::MiddleButton}) {
      sendMouse(view, QEvent::MouseButtonPress, at, button, button);
      sendMouse(view, QEvent::MouseButtonRelease, at, button, Qt::NoButton);
      QApplication::processEvents();
      QCOMPARE(view->renders(), rendered);
    }
    vtkCamera* camera = view->renderer()->GetActiveCamera();
    double before[3];
    camera->GetPosition(before);
    sendMouse(view, QEvent::MouseButtonPress, at, Qt::RightButton, Qt::RightButton);
    for (int step = 1; step <= 5; ++step) sendMouse(view, QEvent::MouseMove, at + QPoint(0, 8 * step), Qt::NoButton, Qt::RightButton);
    sendMouse(view, QEvent::MouseButtonRelease, at + QPoint(0, 40), Qt::RightButton, Qt::NoButton);
    QApplication::processEvents();
    double after[3];
    camera->GetPosition(after);
    QVERIFY(before[0] != after[0] || before[1] != after[1] || before[2] != after[2]);
    QCOMPARE(view->renders(), rendered + 1);
  }

  // A repaint nothing asked for (Qt repaints the view when its window is activated or
  // deactivated, and again after the frame its resize event drew) shows VTK's last frame again
  // instead of rendering the same pixels anew; requestRender() and a new size render a frame.
  void aRepaintNothingAskedForShowsTheLastFrame() {
    QWidget window;
    window.resize(400, 300);
    auto* view = new ffdkit::app::VtkViewWidget(&window);
    view->setGeometry(0, 0, 300, 200);
    view->renderer()->SetBackground(0.2, 0.4, 0.6);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    const QImage first = view->grabFramebuffer();
    QApplication::processEvents();
    const std::uint64_t rendered = view->renders();
    QVERIFY(rendered >= 1);
    QVERIFY(first.size() == view->size() * view->devicePixelRatio());
    const QVector3D blue = meanColour(first, QPoint(first.width() / 2, first.height() / 2), 2);
    QVERIFY2((blue - QVector3D(51, 102, 153)).length() < 3.0f,
             qPrintable(QString("not the background: %1 %2 %3").arg(blue.x()).arg(blue.y()).arg(blue.z())));

    view->update();
    QApplication::processEvents();
    QCOMPARE(view->grabFramebuffer(), first);  // grabFramebuffer repaints: the same pixels
    QCOMPARE(view->renders(), rendered);

    view->renderer()->SetBackground(0.6, 0.4, 0.2);
    view->requestRender();
    const QImage changed = view->grabFramebuffer();
    QCOMPARE(view->renders(), rendered + 1);
    const QVector3D orange = meanColour(changed, QPoint(changed.width() / 2, changed.height() / 2), 2);
    QVERIFY2((orange - QVector3D(153, 102, 51)).length() < 3.0f,
             qPrintable(QString("not the new background: %1 %2 %3").arg(orange.x()).arg(orange.y()).arg(orange.z())));

    // A new size: one frame, drawn in Qt's resize event; the update after it shows that frame.
    view->resize(320, 240);
    QApplication::processEvents();
    QCOMPARE(view->renders(), rendered + 2);
    const QImage resized = view->grabFramebuffer();
    QCOMPARE(view->renders(), rendered + 2);
    QCOMPARE(resized.size(), view->size() * view->devicePixelRatio());
    QVERIFY((meanColour(resized, QPoint(resized.width() - 5, resized.height() - 5), 2) - orange).length() < 3.0f);
  }
};

int main(int argc, char** argv) { return ffdkit::app::testing::runGuiTest<VtkViewWidgetTest>(argc, argv); }

#include "vtk_view_widget_test.moc"
