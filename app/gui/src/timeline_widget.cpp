#include "timeline_widget.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include <QAction>
#include <QApplication>
#include <QDockWidget>
#include <QHBoxLayout>
#include <QLabel>
#include <QMainWindow>
#include <QMenu>
#include <QMenuBar>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>
#include <QToolButton>

namespace ffdkit::app {

/// The ruler: frames left to right, the keys of the selection as diamonds, the current frame as a
/// line with its number. Pressing or dragging on it scrubs (object name "timelineBar").
class TimelineBar : public QWidget {
 public:
  TimelineBar(Timeline& timeline, const scenes::Scene& scene, std::function<void(int)> scrub)
      : timeline_(timeline), scene_(scene), scrub_(std::move(scrub)) {
    setObjectName("timelineBar");
    setMinimumHeight(34);
    setMinimumWidth(60);
    setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
    setCursor(Qt::SizeHorCursor);
  }

  /// The x (widget pixels) of `frame`, and the whole frame nearest to x.
  double xOf(double frame) const {
    const auto& a = scene_.animation();
    const double span = std::max(1, a.lastFrame - a.firstFrame);
    return kMargin + (frame - a.firstFrame) / span * (width() - 2 * kMargin);
  }
  int frameAt(double x) const {
    const auto& a = scene_.animation();
    const double span = std::max(1, a.lastFrame - a.firstFrame);
    return static_cast<int>(std::lround(a.firstFrame + (x - kMargin) / std::max(1.0, width() - 2.0 * kMargin) * span));
  }

 protected:
  void paintEvent(QPaintEvent*) override {
    QPainter p(this);
    p.setRenderHint(QPainter::Antialiasing);
    p.fillRect(rect(), palette().base());
    const auto& a = scene_.animation();
    const int axis = height() - 12;
    // Ticks: a step of 1, 2, 5, 10, 20, 50, ... frames leaving at least 40 pixels between labels.
    int step = 1;
    for (int k = 0; (xOf(a.firstFrame + step) - xOf(a.firstFrame)) < 40.0 && k < 24; ++k) step = (k % 3 == 1 ? 5 : 2) * (step / (k % 3 == 1 ? 2 : 1));
    p.setPen(palette().color(QPalette::Mid));
    p.drawLine(QPointF(xOf(a.firstFrame), axis), QPointF(xOf(a.lastFrame), axis));
    p.setPen(palette().color(QPalette::Text));
    const int first = static_cast<int>(std::ceil(double(a.firstFrame) / step)) * step;
    for (int f = first; f <= a.lastFrame; f += step) {
      const double x = xOf(f);
      p.drawLine(QPointF(x, axis - 4), QPointF(x, axis + 4));
      p.drawText(QRectF(x - 20, axis + 1, 40, 12), Qt::AlignHCenter | Qt::AlignTop, QString::number(f));
    }
    // Keys of the selection.
    p.setPen(QPen(QColor(60, 50, 0), 1));
    p.setBrush(QColor(240, 200, 40));
    for (double f : timeline_.keyFrames()) {
      if (f < a.firstFrame - 1e-9 || f > a.lastFrame + 1e-9) continue;
      const double x = xOf(f), y = axis - 12;
      QPainterPath diamond;
      diamond.moveTo(x, y - 6);
      diamond.lineTo(x + 5, y);
      diamond.lineTo(x, y + 6);
      diamond.lineTo(x - 5, y);
      diamond.closeSubpath();
      p.drawPath(diamond);
    }
    // The current frame.
    const double x = xOf(timeline_.frame());
    p.setPen(QPen(QColor(70, 140, 255), 2));
    p.drawLine(QPointF(x, 2), QPointF(x, axis + 4));
    p.setBrush(QColor(70, 140, 255));
    const QRectF tag(x - 16, 0, 32, 13);
    p.drawRoundedRect(tag, 3, 3);
    p.setPen(Qt::white);
    p.drawText(tag, Qt::AlignCenter, QString::number(timeline_.frame()));
  }
  void mousePressEvent(QMouseEvent* e) override {
    if (e->button() == Qt::LeftButton) scrub_(frameAt(e->position().x()));
  }
  void mouseMoveEvent(QMouseEvent* e) override {
    if (e->buttons() & Qt::LeftButton) scrub_(frameAt(e->position().x()));
  }

 private:
  static constexpr double kMargin = 18.0;
  Timeline& timeline_;
  const scenes::Scene& scene_;
  std::function<void(int)> scrub_;
};

TimelineWidget::TimelineWidget(scenes::Scene& scene, scenes::CommandStack& commands, InteractionController& controller,
                               QWidget* parent)
    : QWidget(parent), timeline_(scene, commands, controller) {
  setObjectName("timeline");
  bar_ = new TimelineBar(timeline_, scene, [this](int frame) {
    if (timeline_.frame() != frame) goTo(frame);
  });
  label_ = new QLabel;
  label_->setObjectName("timelineLabel");
  menu_ = new QMenu(tr("&Animation"), this);
  const auto add = [this](const QString& text, const char* name, auto slot) {
    QAction* a = menu_->addAction(text);
    a->setObjectName(name);
    connect(a, &QAction::triggered, this, [this, slot] { guarded(slot); });
    return a;
  };
  QAction* insert = add(tr("&Insert Key"), "actionInsertKey", [this] { timeline_.insertKeys(); });
  QAction* remove = add(tr("&Delete Key"), "actionDeleteKey", [this] { timeline_.deleteKeys(); });
  menu_->addSeparator();
  play_ = add(tr("&Play"), "actionPlayPause", [this] { togglePlay(); });
  QAction* previous = add(tr("Jump to P&revious Key"), "actionPreviousKey", [this] {
    if (const auto f = timeline_.previousKey()) goTo(static_cast<int>(std::floor(*f)));
  });
  QAction* next = add(tr("Jump to &Next Key"), "actionNextKey", [this] {
    if (const auto f = timeline_.nextKey()) goTo(static_cast<int>(std::ceil(*f)));
  });
  // Short faces for the buttons (the menu keeps the words, the tooltips name the keys).
  previous->setIconText(QString::fromUtf8("\u25C0\u25C6"));
  play_->setIconText(QString::fromUtf8("\u25B6"));
  next->setIconText(QString::fromUtf8("\u25C6\u25B6"));
  insert->setIconText(QString::fromUtf8("+\u25C6"));
  remove->setIconText(QString::fromUtf8("\u2212\u25C6"));
  // Window-wide keys: the actions live in the window (its menu bar), not only on this widget.
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(4, 2, 4, 2);
  // A narrow window squeezes the timeline (clipping it) rather than the docks beside the view.
  layout->setSizeConstraint(QLayout::SetNoConstraint);
  for (QAction* a : {previous, play_, next, insert, remove}) {
    auto* button = new QToolButton;
    button->setDefaultAction(a);
    button->setAutoRaise(true);
    button->setFocusPolicy(Qt::NoFocus);
    layout->addWidget(button);
  }
  layout->addWidget(bar_, 1);
  layout->addWidget(label_);
  playTimer_.setTimerType(Qt::PreciseTimer);
  connect(&playTimer_, &QTimer::timeout, this, [this] { tick(); });
  sync();
}

QSize TimelineWidget::minimumSizeHint() const { return {0, QWidget::minimumSizeHint().height()}; }

template <class F>
void TimelineWidget::guarded(F f) {
  try {
    f();
  } catch (const std::exception& e) {
    emit error(QString::fromStdString(e.what()));
    QApplication::beep();
  }
  sync();
}

void TimelineWidget::goTo(int frame) {
  guarded([&] { timeline_.setFrame(frame); });
  emit frameChanged();
}

void TimelineWidget::sync() {
  const scenes::Animation& a = timeline_.scene().animation();
  label_->setText(tr("frame %1  (%2..%3, %4 fps)")
                      .arg(timeline_.frame())
                      .arg(a.firstFrame)
                      .arg(a.lastFrame)
                      .arg(a.framesPerSecond, 0, 'g', 4));
  BarContent content{a.firstFrame, a.lastFrame, timeline_.frame(), timeline_.keyFrames()};
  if (content == barShown_) return;
  barShown_ = std::move(content);
  bar_->update();
}

void TimelineWidget::togglePlay() {
  timeline_.setPlaying(!timeline_.playing());
  play_->setText(timeline_.playing() ? tr("&Pause") : tr("&Play"));
  play_->setIconText(QString::fromUtf8(timeline_.playing() ? "\u275A\u275A" : "\u25B6"));
  if (timeline_.playing()) {
    playedFrames_ = 0;
    if (!stepped_) startPlayTimer();
  } else {
    playTimer_.stop();
    emit frameChanged();
  }
}

void TimelineWidget::startPlayTimer() {
  clock_.start();
  playTimer_.start(std::max(1, static_cast<int>(std::lround(1000.0 / timeline_.scene().animation().framesPerSecond))));
}

void TimelineWidget::setSteppedPlayback(bool stepped) {
  if (stepped == stepped_) return;
  stepped_ = stepped;
  if (stepped_) playTimer_.stop();
  else if (timeline_.playing()) startPlayTimer();
}

template <class Move>
bool TimelineWidget::advance(Move move) {
  bool changed = false;
  guarded([&] { changed = move(); });
  if (changed) ++playedFrames_;
  return changed;
}

bool TimelineWidget::stepPlayback(int frames) {
  return advance([&] { return timeline_.advanceFrames(frames); });
}

void TimelineWidget::tick() {
  const double elapsed = clock_.nsecsElapsed() * 1e-9;
  clock_.restart();
  advance([&] { return timeline_.advance(elapsed); });
  // A periodic timer at the frame rate: a frame slower than that delays the next tick (Qt does
  // not queue missed ticks) and the wall-time clock makes playback skip frames instead of slowing
  // down. Events are handled between ticks, so the window stays responsive (Pause, scrubbing).
}

TimelineWidget* addTimelineDock(QMainWindow* window, scenes::Scene& scene, scenes::CommandStack& commands,
                                InteractionController& controller) {
  auto* timeline = new TimelineWidget(scene, commands, controller);
  auto* dock = new QDockWidget(QObject::tr("Timeline"), window);
  dock->setObjectName("timelineDock");
  dock->setWidget(timeline);
  dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetClosable);
  // Under the view only: the side docks keep the bottom corners.
  window->setCorner(Qt::BottomLeftCorner, Qt::LeftDockWidgetArea);
  window->setCorner(Qt::BottomRightCorner, Qt::RightDockWidgetArea);
  window->addDockWidget(Qt::BottomDockWidgetArea, dock);
  window->menuBar()->addMenu(timeline->menu());
  return timeline;
}

}  // namespace ffdkit::app
