// The timeline under the 3D view (docs/animation.md): a ruler of the scene's frame range with the
// current frame and the keys of the selection, scrubbed by dragging; play / pause at the scene's
// frame rate; jump to the previous / next key; Insert Key and Delete Key. A thin Qt layer over
// app::Timeline (the headless logic, app/interaction).
#pragma once

#include <optional>
#include <vector>

#include <QElapsedTimer>
#include <QTimer>
#include <QWidget>

#include "ffdkit/interaction/timeline.h"

class QAction;
class QLabel;
class QMainWindow;
class QMenu;
class QToolButton;

namespace ffdkit::app {

class TimelineBar;

class TimelineWidget : public QWidget {
  Q_OBJECT
 public:
  TimelineWidget(scenes::Scene& scene, scenes::CommandStack& commands, InteractionController& controller,
                 QWidget* parent = nullptr);

  Timeline& timeline() { return timeline_; }
  /// The Animation menu: Insert Key (actionInsertKey), Delete Key (actionDeleteKey), Play / Pause
  /// (actionPlayPause), Previous Key (actionPreviousKey), Next Key (actionNextKey); their keys
  /// come from keyboard_shortcuts.
  QMenu* menu() const { return menu_; }
  /// Goes to `frame` (Timeline::setFrame), redraws and emits frameChanged.
  void goTo(int frame);
  /// Redraws the ruler, the marks and the frame label (after any change of the scene or selection).
  void sync();
  /// Frames shown by playback since it last started (for measuring playback speed).
  int playedFrames() const { return playedFrames_; }
  /// Where playback's time comes from. Off (the app): a timer at the scene's frame rate moves
  /// playback by the wall-clock time since its last tick (Timeline::advance), so which frames a
  /// run shows depends on how fast the machine is. On: Play starts no timer and playback moves
  /// only by stepPlayback(), so a scripted run (a test) shows the same frames every time.
  /// Switching while playing stops or starts the timer.
  void setSteppedPlayback(bool stepped);
  bool steppedPlayback() const { return stepped_; }
  /// Moves playback on by `frames` whole frames (Timeline::advanceFrames) when it is playing
  /// (stepped or not); nothing otherwise. @return whether the frame changed.
  bool stepPlayback(int frames = 1);
  QSize minimumSizeHint() const override;

 signals:
  /// An operation was refused or failed (the window says it in its status line).
  void error(const QString& message);
  /// The current frame was set by a scrub, a jump or a pause (not at each frame of playback):
  /// the window refreshes what shows the widgets' values (the property panel).
  void frameChanged();

 private:
  void togglePlay();
  void startPlayTimer();
  void tick();
  /// Runs `move` (a Timeline::advance), saying its errors; counts a frame shown.
  /// @return whether the frame changed.
  template <class Move>
  bool advance(Move move);
  template <class F>
  void guarded(F f);

  Timeline timeline_;
  TimelineBar* bar_ = nullptr;
  /// What the bar draws of the document: the frame range, the frame and the selection's keys.
  struct BarContent {
    int firstFrame = 0;
    int lastFrame = 0;
    int frame = 0;
    std::vector<double> keyFrames;
    friend bool operator==(const BarContent&, const BarContent&) = default;
  };
  /// The bar's content as sync() last had it drawn: a change that leaves it (a hover, a drag of a
  /// widget without keys) repaints nothing of the timeline.
  std::optional<BarContent> barShown_;
  QLabel* label_ = nullptr;
  QMenu* menu_ = nullptr;
  QAction* play_ = nullptr;
  QTimer playTimer_;
  QElapsedTimer clock_;
  int playedFrames_ = 0;
  bool stepped_ = false;  ///< playback moves by stepPlayback() only (setSteppedPlayback)
};

/// Puts a timeline in a dock under the 3D view of `window` (between the side docks) and its
/// Animation menu in the menu bar. @return the timeline widget (object name "timeline").
TimelineWidget* addTimelineDock(QMainWindow* window, scenes::Scene& scene, scenes::CommandStack& commands,
                                InteractionController& controller);

}  // namespace ffdkit::app
