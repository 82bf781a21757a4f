// The timeline under real events (Xvfb): I inserts a key (one undo step), scrubbing the ruler with
// the mouse sets the widget to the interpolated value, Space plays and pauses, Alt+Right / Alt+Left
// jump between keys, Alt+I deletes the key and Ctrl+Z brings it back.
#include <QAction>
#include <QDoubleSpinBox>

#include <cmath>
#include <filesystem>

#include "ffdkit/scenes/animation.h"
#include "gui_test_support.h"
#include "timeline_widget.h"

using namespace ffdkit;
using namespace ffdkit::app::testing;
using app::MainWindow;

namespace {

// Where the ruler draws `frame`: an 18-pixel margin each side, the range spread between
// (TimelineBar's layout, written out independently here).
QPoint rulerPoint(QWidget* bar, const scenes::Animation& a, int frame) {
  const double x = 18.0 + double(frame - a.firstFrame) / (a.lastFrame - a.firstFrame) * (bar->width() - 36.0);
  return QPoint(static_cast<int>(std::lround(x)), bar->height() / 2);
}

class TimelineGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void keysScrubPlayAndUndo() {
    auto w = openWindow(QSize(1280, 800));
    QVERIFY(w);
    w->openScene(kExamples / "default");
    const scenes::Scene& scene = w->scene();
    const widgets::WidgetId pull = scene.widgets.find("pull");
    auto* timeline = w->findChild<app::TimelineWidget*>("timeline");
    QVERIFY(timeline);
    QWidget* bar = w->findChild<QWidget*>("timelineBar");
    QVERIFY(bar && bar->isVisible());
    const scenes::Animation& a = scene.animation();
    QCOMPARE(a.lastFrame, 72);

    // Scrub with the mouse to frame 12: between the keys 0 (frame 0) and 0.5 (frame 24), both
    // flat (an end and a peak), the Hermite midpoint is their mean.
    clickRow(*w, "pull");
    QTest::mouseClick(bar, Qt::LeftButton, Qt::NoModifier, rulerPoint(bar, a, 12));
    QCOMPARE(timeline->timeline().frame(), 12);
    QVERIFY(std::abs(scene.widgets.variation(pull) - 0.25) < 1e-12);
    // The property panel shows the value of the frame, not the one before the scrub.
    QApplication::processEvents();    // the panel's new rows show on a queued call
    QDoubleSpinBox* field = nullptr;  // the panel's shown row (rows it replaced wait hidden for deletion)
    for (auto* box : w->findChildren<QDoubleSpinBox*>("variation"))
      if (box->isVisible()) field = box;
    QVERIFY(field);
    QCOMPARE(field->value(), 0.25);

    // Drag the arrow up, then I keys the new value at frame 12: one undo step.
    dragArrow(*w, pull, 0.1);
    const double keyed = scene.widgets.variation(pull);
    QVERIFY(keyed > 0.3 && keyed < 0.4);
    const std::size_t steps = w->commands().position();
    pressKey(*w, Qt::Key_I);
    QCOMPARE(w->commands().position(), steps + 1);
    QCOMPARE(QString::fromStdString(w->commands().undoDescription()), QString("Insert Key"));
    const double t12 = scenes::frameTime(a, 12);
    const auto key = scenes::keyAt(a, pull, scenes::ChannelKind::Variation, t12);
    QVERIFY(key);
    QCOMPARE(key->variation, keyed);

    // Scrub by dragging from frame 30 to frame 6: the value is the smooth curve's at frame 6.
    // Keys (0 s, 0), (0.5 s, v), (1 s, 0.5): slope 0 at the first key, (0.5 - 0) / (1 - 0) = 0.5
    // at the middle one (0 < v < 0.5); at s = 1/2, h = 0.5: v / 2 - (1/8)(0.5)(0.5).
    QTest::mousePress(bar, Qt::LeftButton, Qt::NoModifier, rulerPoint(bar, a, 30));
    for (int f = 28; f >= 6; f -= 2) QTest::mouseMove(bar, rulerPoint(bar, a, f));
    QTest::mouseRelease(bar, Qt::LeftButton, Qt::NoModifier, rulerPoint(bar, a, 6));
    QCOMPARE(timeline->timeline().frame(), 6);
    QVERIFY(std::abs(scene.widgets.variation(pull) - (keyed / 2 - 0.03125)) < 1e-12);
    QCOMPARE(w->commands().position(), steps + 1);  // scrubbing is not an edit

    // Space plays at the scene's rate; Space again pauses.
    pressKey(*w, Qt::Key_Space);
    QVERIFY(timeline->timeline().playing());
    QTest::qWait(600);  // ~14 frames at 24 fps
    pressKey(*w, Qt::Key_Space);
    QVERIFY(!timeline->timeline().playing());
    const int reached = timeline->timeline().frame();
    QVERIFY2(reached > 6 + 3, qPrintable(QString("frame %1 after 0.6 s of play").arg(reached)));
    QVERIFY(timeline->playedFrames() >= 3);
    QTest::qWait(200);
    QCOMPARE(timeline->timeline().frame(), reached);  // paused

    // Jump between the selection's keys: Alt+Left / Alt+Right.
    QTest::mouseClick(bar, Qt::LeftButton, Qt::NoModifier, rulerPoint(bar, a, 18));
    pressKey(*w, Qt::Key_Left, Qt::AltModifier);
    QCOMPARE(timeline->timeline().frame(), 12);
    pressKey(*w, Qt::Key_Right, Qt::AltModifier);
    QCOMPARE(timeline->timeline().frame(), 24);
    pressKey(*w, Qt::Key_Left, Qt::AltModifier);
    QCOMPARE(timeline->timeline().frame(), 12);
    QVERIFY(std::abs(scene.widgets.variation(pull) - keyed) < 1e-12);

    // Alt+I deletes the key at frame 12 (one step); Ctrl+Z brings it back, with its value.
    pressKey(*w, Qt::Key_I, Qt::AltModifier);
    QVERIFY(!scenes::keyAt(a, pull, scenes::ChannelKind::Variation, t12));
    QCOMPARE(w->commands().position(), steps + 2);
    QCOMPARE(QString::fromStdString(w->commands().undoDescription()), QString("Delete Key"));
    pressKey(*w, Qt::Key_Z, Qt::ControlModifier);
    const auto back = scenes::keyAt(a, pull, scenes::ChannelKind::Variation, t12);
    QVERIFY(back);
    QCOMPARE(back->variation, keyed);
    // Undo once more: the inserted key goes, and the scene's keys are the file's again.
    pressKey(*w, Qt::Key_Z, Qt::ControlModifier);
    QVERIFY(!scenes::keyAt(a, pull, scenes::ChannelKind::Variation, t12));
    QCOMPARE(scenes::keyTimes(scene), (std::vector<double>{0.0, 1.0, 2.0, 3.0}));
  }

  // Playback draws a frame only where a key moves something: over a scene without keys the
  // timeline's frame moves on and the view keeps showing its last frame (nothing it draws
  // changed); over the default scene, whose key moves 'pull' at every frame, each step draws one.
  void playbackDrawsOnlyTheFramesAKeyMovesSomethingAt() {
    auto w = openWindow(QSize(640, 480));
    QVERIFY(w);
    auto* timeline = w->findChild<app::TimelineWidget*>("timeline");
    QVERIFY(timeline);
    timeline->setSteppedPlayback(true);
    for (const char* scene : {"cylinder-twist", "default"}) {
      w->openScene(kExamples / scene);
      const bool keyed = !scenes::keyTimes(w->scene()).empty();
      QCOMPARE(keyed, std::string(scene) == "default");
      pressKey(*w, Qt::Key_Space);
      QVERIFY(timeline->timeline().playing());
      QApplication::processEvents();
      const std::uint64_t rendered = w->view()->renders();
      const int frame = timeline->timeline().frame();
      for (int step = 1; step <= 5; ++step) {
        QVERIFY(timeline->stepPlayback(1));
        QApplication::processEvents();
        QCOMPARE(timeline->timeline().frame(), frame + step);
        QCOMPARE(w->view()->renders(), rendered + (keyed ? std::uint64_t(step) : 0));
      }
      pressKey(*w, Qt::Key_Space);
      QVERIFY(!timeline->timeline().playing());
    }
  }

  // The ruler repaints only when what it draws changes: a hover over a widget's glyph changes
  // the view's highlight, not the frame, the range or the keys shown; a frame step moves it.
  void theRulerRepaintsOnlyWhenItsContentChanges() {
    auto w = openWindow(QSize(1280, 800));
    QVERIFY(w);
    w->openScene(kExamples / "default");
    QWidget* bar = w->findChild<QWidget*>("timelineBar");
    QVERIFY(bar && bar->isVisible());
    struct PaintCounter : QObject {
      int paints = 0;
      bool eventFilter(QObject*, QEvent* event) override {
        if (event->type() == QEvent::Paint) ++paints;
        return false;
      }
    } counter;
    QApplication::processEvents();
    bar->installEventFilter(&counter);
    const widgets::WidgetModel& m = w->scene().widgets;
    const widgets::WidgetId pull = m.find("pull");
    const widgets::WidgetFrame f = m.affineFrame(pull);
    for (int axis = 0; axis < 3 && w->controller().highlights().hovered != pull; ++axis)
      for (double along = 0.3; along < 1.0 && w->controller().highlights().hovered != pull; along += 0.1)
        hover(*w, toWidget(*w, f.frame.translation() + along * f.size * f.frame.linear().col(axis)));
    QVERIFY(w->controller().highlights().hovered == pull);
    QApplication::processEvents();
    QCOMPARE(counter.paints, 0);
    auto* timeline = w->findChild<app::TimelineWidget*>("timeline");
    timeline->goTo(timeline->timeline().frame() + 1);
    QApplication::processEvents();
    QCOMPARE(counter.paints, 1);
    bar->removeEventFilter(&counter);
  }

  void insertKeyWithNothingKeyableSaysWhy() {
    auto w = openWindow(QSize(1280, 800));
    QVERIFY(w);
    w->openScene(kExamples / "default");
    clickRow(*w, "top");  // a cell
    const std::size_t steps = w->commands().position();
    pressKey(*w, Qt::Key_I);
    QCOMPARE(w->commands().position(), steps);
    QVERIFY2(w->statusMessage().contains("Insert Key"), qPrintable(w->statusMessage()));
  }
};

}  // namespace

int main(int argc, char** argv) { return runGuiTest<TimelineGuiTest>(argc, argv); }

#include "timeline_gui_test.moc"
