// One evaluation per event-loop tick (MainWindow::Impl::drawFrame): the window evaluates the scene
// once, at its next frame, for all the events the tick delivered, whatever they were (pointer
// moves of a drag, undo and redo, hover). Real events posted to the event loop, as the window
// system delivers them; the deformed points checked against a separate evaluation.
#include <QAction>
#include <QApplication>
#include <QMouseEvent>
#include <QTest>

#include <cmath>
#include <numbers>

#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "gui_test_support.h"

using namespace ffdkit;
using namespace ffdkit::app::testing;
using app::MainWindow;
using widgets::WidgetId;

namespace {

// Posts a mouse event to the view: delivered by the event loop, in order, as the window system's.
void postMouse(MainWindow& w, QEvent::Type type, QPoint at, Qt::MouseButton button, Qt::MouseButtons buttons) {
  QWidget* view = w.view();
  QApplication::postEvent(view, new QMouseEvent(type, QPointF(at), view->mapToGlobal(QPointF(at)), button, buttons,
                                                Qt::NoModifier));
}

// Delivers everything posted so far and whatever that posts (the frame), until the loop is idle.
void deliverTick() {
  for (int i = 0; i < 5; ++i) QApplication::processEvents();
}

// The largest difference between every object's points in the window and in a deformer of its own.
double differenceFromASeparateEvaluation(MainWindow& w) {
  const auto expected = scenes::deformScene(w.scene());
  double worst = 0.0;
  for (const auto& [name, points] : expected)
    worst = std::max(worst, (w.deformer().points(name) - points).cwiseAbs().maxCoeff());
  return worst;
}

}  // namespace

class EvaluationTickGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    window_ = startWindow(QSize(), StartSettings::Kept, kExamples / "press");
    QVERIFY(window_ != nullptr);
    window_->view()->grabFramebuffer();
    deliverTick();
  }
  void cleanup() { window_.reset(); }

  // Three pointer moves of a drag in one tick: each moves the crank, one evaluation draws them.
  void threeMovesOfADragInOneTickAreOneEvaluation() {
    MainWindow& w = *window_;
    const auto& m = w.scene().widgets;
    const WidgetId handle = m.find("handle");
    const widgets::WidgetFrame f = m.affineFrame(handle);
    const Eigen::Vector3d o = f.frame.translation(), x = f.frame.linear().col(0), y = f.frame.linear().col(1);
    const double start = m.variation(handle);
    auto onCircle = [&](double angle) { return Eigen::Vector3d(o + f.size * (std::cos(angle) * x + std::sin(angle) * y)); };

    postMouse(w, QEvent::MouseButtonPress, toWidget(w, onCircle(start)), Qt::LeftButton, Qt::LeftButton);
    deliverTick();
    QVERIFY2(w.controller().dragging(), "the press grabbed the crank");
    const std::uint64_t before = w.evaluations();
    // The deformer's own count of point changes of the pressed object (not the window's).
    const std::string object = w.scene().objects().front().name;
    const std::uint64_t revision = w.deformer().revision(object);
    for (int step = 1; step <= 3; ++step)
      postMouse(w, QEvent::MouseMove, toWidget(w, onCircle(start + step * std::numbers::pi / 12)), Qt::NoButton, Qt::LeftButton);
    QCOMPARE(w.evaluations(), before);  // nothing delivered yet
    deliverTick();
    QCOMPARE(w.deformer().revision(object), revision + 1);
    QCOMPARE(w.evaluations(), before + 1);
    QVERIFY2(std::abs(m.variation(handle) - start - 3 * std::numbers::pi / 12) < 0.05,
             qPrintable(QString::number(m.variation(handle) - start)));  // all three moves were handled
    // During the drag the points are deltas from the last exact evaluation (~1e-16 relative).
    QVERIFY2(differenceFromASeparateEvaluation(w) < 1e-12, qPrintable(QString::number(differenceFromASeparateEvaluation(w))));

    postMouse(w, QEvent::MouseButtonRelease, toWidget(w, onCircle(start + std::numbers::pi / 4)), Qt::LeftButton, Qt::NoButton);
    deliverTick();
    QCOMPARE(w.evaluations(), before + 2);  // the release's exact result
    QCOMPARE(differenceFromASeparateEvaluation(w), 0.0);
  }

  // Undo twice in one tick (the two steps queued): one evaluation, at the document's start.
  void twoUndosInOneTickAreOneEvaluation() {
    MainWindow& w = *window_;
    const auto& m = w.scene().widgets;
    const WidgetId handle = m.find("handle");
    const double start = m.variation(handle);
    const auto startPoints = scenes::deformScene(w.scene());
    for (double turn : {0.3, 0.2}) {
      const widgets::WidgetFrame f = m.affineFrame(handle);
      const Eigen::Vector3d o = f.frame.translation(), x = f.frame.linear().col(0), y = f.frame.linear().col(1);
      const double now = m.variation(handle);
      dragWorld(w, o + f.size * (std::cos(now) * x + std::sin(now) * y),
                o + f.size * (std::cos(now + turn) * x + std::sin(now + turn) * y));
      click(w, QPoint(5, 5));  // another gesture next: the two drags stay two steps
    }
    deliverTick();
    QVERIFY(std::abs(m.variation(handle) - start) > 0.2);
    const std::uint64_t before = w.evaluations();
    const std::string object = w.scene().objects().front().name;
    const std::uint64_t revision = w.deformer().revision(object);
    QAction* undo = action(w, "actionUndo");
    QMetaObject::invokeMethod(undo, &QAction::trigger, Qt::QueuedConnection);
    QMetaObject::invokeMethod(undo, &QAction::trigger, Qt::QueuedConnection);
    deliverTick();
    QCOMPARE(w.deformer().revision(object), revision + 1);
    QCOMPARE(w.evaluations(), before + 1);
    QCOMPARE(m.variation(handle), start);
    for (const auto& [name, points] : startPoints) QCOMPARE((w.deformer().points(name) - points).cwiseAbs().maxCoeff(), 0.0);
  }

  // Hover moves change highlights only: frames are drawn, nothing is evaluated.
  void hoverIsNoEvaluation() {
    MainWindow& w = *window_;
    const std::uint64_t before = w.evaluations();
    for (int i = 0; i < 3; ++i) postMouse(w, QEvent::MouseMove, QPoint(100 + 40 * i, 200), Qt::NoButton, Qt::NoButton);
    deliverTick();
    QCOMPARE(w.evaluations(), before);
  }

 private:
  std::unique_ptr<MainWindow> window_;
};

int main(int argc, char** argv) { return runGuiTest<EvaluationTickGuiTest>(argc, argv); }

#include "evaluation_tick_gui_test.moc"
