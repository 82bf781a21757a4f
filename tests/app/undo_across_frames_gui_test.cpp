// Undo and redo after a frame change, in the real window (Xvfb, real Qt mouse and key events).
// An edit's command holds the values it changed as they were at the frame it was made; after the
// timeline has moved, Ctrl+Z must give the document as it was before the edit, carried to the
// frame shown, and every frame after that must show what the unedited document shows there.
// The expectations are built apart from the window: the sample file read again and set to the
// same frames by scenes::applyAnimationFrame, or the edited document's text read back.
#include <QTest>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <sstream>

#include "ffdkit/interaction/edit_controller.h"
#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/scene_file.h"
#include "gui_test_support.h"
#include "number_text_difference.h"
#include "timeline_widget.h"

using namespace ffdkit;
using namespace ffdkit::app::testing;
using app::MainWindow;

namespace {

const std::filesystem::path kDefault = FFDKIT_SOURCE_DIR "/scenes/examples/default";

// Relative to max(1, |x|): rounding of a few gestures (frame-0 points written back at frame 24 are 0.43 off).
constexpr double kRounding = 1e-12;

// Where the ruler draws `frame`: an 18-pixel margin each side, the range spread between
// (TimelineBar's layout, written out independently here as in timeline_gui_test).
QPoint rulerPoint(QWidget* bar, const scenes::Animation& a, int frame) {
  const double x = 18.0 + double(frame - a.firstFrame) / (a.lastFrame - a.firstFrame) * (bar->width() - 36.0);
  return QPoint(static_cast<int>(std::lround(x)), bar->height() / 2);
}

// The default sample read from its file and taken through `frames` in turn, as the timeline does.
std::string fileThroughFrames(std::initializer_list<int> frames) {
  scenes::Scene scene = scenes::readScene(kDefault);
  for (int f : frames) scenes::applyAnimationFrame(scene, f);
  return scenes::sceneFileText(scene);
}

// A document's text read back (objects rebuilt from their sources) and taken to `frame`.
std::string textAtFrame(const std::string& text, int frame) {
  std::istringstream in(text);
  scenes::Scene scene = scenes::readScene(in, "edited.json", {.baseDirectory = kDefault});
  scenes::applyAnimationFrame(scene, frame);
  return scenes::sceneFileText(scene);
}

// The first line where two documents differ, for a failure message.
std::string firstDifference(const std::string& got, const std::string& want) {
  std::istringstream a(got), b(want);
  std::string x, y;
  for (int line = 1;; ++line) {
    const bool moreA = static_cast<bool>(std::getline(a, x)), moreB = static_cast<bool>(std::getline(b, y));
    if (!moreA && !moreB) return "same";
    if (x != y || moreA != moreB) return "line " + std::to_string(line) + ": got '" + x + "', want '" + y + "'";
  }
}

// Types `text` on the view, key by key.
void typeKeys(MainWindow& w, const std::string& text) {
  for (char c : text) {
    const Qt::Key key = c == '.' ? Qt::Key_Period : c == '-' ? Qt::Key_Minus : static_cast<Qt::Key>(Qt::Key_0 + (c - '0'));
    pressKey(w, key);
  }
}

}  // namespace

class UndoAcrossFramesGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    window_ = startWindow(QSize(1100, 800), StartSettings::Kept, kDefault);
    QVERIFY(window_ != nullptr);
    bar_ = window_->findChild<QWidget*>("timelineBar");
    timeline_ = window_->findChild<app::TimelineWidget*>("timeline");
    QVERIFY(bar_ && bar_->isVisible() && timeline_);
    // The sample's pull is keyed 0, 0.5, -0.2, 0 at frames 0, 24, 48, 72 (3 s at 24 fps).
    QCOMPARE(window_->scene().animation().lastFrame, 72);
    // Scrub to frame 12 and back: the model is the animation's at frame 0 from here on.
    goTo(12);
    goTo(0);
    QCOMPARE(scenes::sceneFileText(window_->scene()), fileThroughFrames({12, 0}));
  }
  void cleanup() { window_.reset(); }

  // G on lattice points (EditController): every point of the lattice moved 0.3 along x at frame
  // 0, the timeline moved to frame 24 (the keyed pull rises 0.5 and lifts its point), Ctrl+Z
  // there. Before the fix the points went back to their frame-0 places under a pull of 0.5: the
  // top centre point 0.5 below where the unedited file has it at frame 24.
  void aTransformUndoneAtAnotherFrameGivesTheUneditedDocumentThere() {
    MainWindow& w = *window_;
    const std::size_t steps = w.commands().position();
    clickRow(w, "lattice");
    pressKey(w, Qt::Key_Tab);
    QVERIFY(w.editController().editing());
    pressKey(w, Qt::Key_A);  // every point
    hover(w, QPoint(w.view()->width() / 2, w.view()->height() / 2));
    pressKey(w, Qt::Key_G);
    pressKey(w, Qt::Key_X);
    typeKeys(w, "0.3");
    pressKey(w, Qt::Key_Return);
    QCOMPARE(w.commands().position(), steps + 1);
    pressKey(w, Qt::Key_Tab);  // out of the edit mode
    const std::string edited = scenes::sceneFileText(w.scene());
    QVERIFY(edited != fileThroughFrames({12, 0}));

    goTo(24);
    QCOMPARE(scenes::sceneFileText(w.scene()), textAtFrame(edited, 24));  // the edit, carried to frame 24
    pressKey(w, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(w.commands().position(), steps);
    expectDocument(fileThroughFrames({12, 0, 24}), "undone at frame 24");
    // Every frame shows what the unedited file shows there.
    for (int f : {0, 48, 72, 36}) {
      goTo(f);
      expectDocument(fileThroughFrames({12, 0, 24, f}), "undone, then frame " + std::to_string(f));
    }
    // Redo at frame 36 (pull between 0.5 and -0.2): the edited document carried to frame 36.
    pressKey(w, Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);
    QCOMPARE(w.commands().position(), steps + 1);
    expectDocument(textAtFrame(edited, 36), "redone at frame 36");
    // And undone once more at frame 48, then back at the first frame: the file's frame 0.
    goTo(48);
    pressKey(w, Qt::Key_Z, Qt::ControlModifier);
    goTo(0);
    expectDocument(fileThroughFrames({12, 0}), "undone at frame 48, then frame 0");
  }

  // A drag of the keyed pull arrow (InteractionController) at frame 0, then frame 12, Ctrl+Z:
  // the pull at frame 12 is the key's 0.25 and the lattice as the unedited file's there (before
  // the fix the drag's start value, 0, was written back at frame 12).
  void aWidgetDragUndoneAtAnotherFrameGivesTheUneditedDocumentThere() {
    MainWindow& w = *window_;
    const widgets::WidgetId pull = w.scene().widgets.find("pull");
    const std::size_t steps = w.commands().position();
    dragArrow(w, pull, 0.2);
    QCOMPARE(w.commands().position(), steps + 1);
    QVERIFY(w.scene().widgets.variation(pull) > 0.1);
    goTo(12);
    pressKey(w, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(w.commands().position(), steps);
    QVERIFY(std::abs(w.scene().widgets.variation(pull) - 0.25) < 1e-12);
    expectDocument(fileThroughFrames({12, 0, 12}), "drag undone at frame 12");
    goTo(0);
    expectDocument(fileThroughFrames({12, 0}), "drag undone at frame 12, then frame 0");
  }

  // Without a frame change, undo writes back exactly what the edit changed (no animation runs):
  // here the pull dragged at frame 0 goes back to the file's value at frame 0, byte for byte.
  void anUndoAtTheSameFrameIsExact() {
    MainWindow& w = *window_;
    const std::string before = scenes::sceneFileText(w.scene());
    dragArrow(w, w.scene().widgets.find("pull"), 0.2);
    QVERIFY(scenes::sceneFileText(w.scene()) != before);
    pressKey(w, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(scenes::sceneFileText(w.scene()), before);
  }

 private:
  void goTo(int frame) {
    QTest::mouseClick(bar_, Qt::LeftButton, Qt::NoModifier, rulerPoint(bar_, window_->scene().animation(), frame));
    QCOMPARE(timeline_->timeline().frame(), frame);
  }
  // The window's document equals `want` but for rounding: the window reached the frame through
  // other gestures than the expectation (an undo goes back to the edit's values and forward
  // again), each exact to a few units in the last place.
  void expectDocument(const std::string& want, const std::string& what) {
    const std::string got = scenes::sceneFileText(window_->scene());
    const std::optional<double> difference = largestNumberDifference(got, want);
    QVERIFY2(difference && *difference <= kRounding,
             (what + (difference ? " (largest difference " + std::to_string(*difference) + ")" : std::string()) + ": " +
              firstDifference(got, want))
                 .c_str());
  }

  std::unique_ptr<MainWindow> window_;
  QWidget* bar_ = nullptr;
  app::TimelineWidget* timeline_ = nullptr;
};

int main(int argc, char** argv) { return runGuiTest<UndoAcrossFramesGuiTest>(argc, argv); }

#include "undo_across_frames_gui_test.moc"
