#include "ffdkit/interaction/timeline.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "ffdkit/scenes/document_delta.h"

namespace ffdkit::app {

using scenes::ChannelKind;
using scenes::Keyframe;
using widgets::WidgetId;

/// One key a command adds, replaces or removes: before and after (nullopt: no key).
struct Timeline::KeyChange {
  WidgetId widget;
  ChannelKind kind;
  double time = 0.0;
  std::optional<Keyframe> before;
  std::optional<Keyframe> after;
};

Timeline::Timeline(scenes::Scene& scene, scenes::CommandStack& commands, InteractionController& controller)
    : scene_(scene), commands_(commands), controller_(controller) {}

int Timeline::frame() const {
  return std::clamp(frame_, scene_.animation().firstFrame, scene_.animation().lastFrame);
}

void Timeline::setFrame(int frame) {
  frame_ = std::clamp(frame, scene_.animation().firstFrame, scene_.animation().lastFrame);
  clock_ = frame_;
  // Undo after this carries what it writes back to the frame shown.
  controller_.animationApplied(scenes::frameTime(scene_.animation(), frame_));
  scenes::applyAnimationFrame(scene_, frame_);
  controller_.refresh();
}

std::vector<std::pair<WidgetId, ChannelKind>> Timeline::selectedChannels() const {
  std::vector<std::pair<WidgetId, ChannelKind>> channels;
  const auto add = [&](WidgetId w, ChannelKind k) {
    if (std::find(channels.begin(), channels.end(), std::make_pair(w, k)) == channels.end()) channels.emplace_back(w, k);
  };
  for (WidgetId w : controller_.selection()) {
    const auto kinds = scenes::keyableKinds(scene_.widgets, w);
    if (!kinds.empty()) add(w, kinds.front());  // variation, or a lattice's frame (else its points)
  }
  if (const auto& point = controller_.pickedPoint(); point && scene_.widgets.contains(point->lattice))
    add(point->lattice, ChannelKind::ControlPoints);
  return channels;
}

std::vector<double> Timeline::keyFrames() const {
  std::vector<double> times;
  const auto& selection = controller_.selection();
  if (selection.empty() && !controller_.pickedPoint()) {
    times = scenes::keyTimes(scene_);
  } else {
    for (const auto& [widget, kind] : selectedChannels()) {
      const std::vector<double> own = scenes::keyTimes(scene_, widget);
      times.insert(times.end(), own.begin(), own.end());
    }
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
  }
  std::vector<double> frames;
  for (double t : times) frames.push_back(scenes::timeFrame(scene_.animation(), t));
  return frames;
}

std::optional<double> Timeline::previousKey() const {
  const auto frames = keyFrames();
  const double now = frame();
  for (auto it = frames.rbegin(); it != frames.rend(); ++it)
    if (*it < now - 1e-6) return *it;
  return std::nullopt;
}

std::optional<double> Timeline::nextKey() const {
  for (double f : keyFrames())
    if (f > frame() + 1e-6) return f;
  return std::nullopt;
}

int Timeline::insertKeys() {
  const auto channels = selectedChannels();
  if (channels.empty())
    throw std::invalid_argument("Insert Key: select an affine widget (its variation) or a lattice (its frame); a picked "
                                "lattice point keys its lattice's control points");
  const double time = scenes::frameTime(scene_.animation(), frame());
  const widgets::WidgetModelState animatedBefore = scenes::animatedState(scene_);
  std::vector<KeyChange> changes;
  for (const auto& [widget, kind] : channels) {
    Keyframe key = scenes::currentKey(scene_, widget, kind, time);
    KeyChange change{widget, kind, time, scenes::setKey(scene_, widget, kind, key), key};
    changes.push_back(std::move(change));
  }
  const int count = static_cast<int>(changes.size());
  push("Insert Key", std::move(changes), animatedBefore);
  return count;
}

int Timeline::deleteKeys() {
  const double time = scenes::frameTime(scene_.animation(), frame());
  const widgets::WidgetModelState animatedBefore = scenes::animatedState(scene_);
  std::vector<KeyChange> changes;
  for (const auto& [widget, kind] : selectedChannels()) {
    // A lattice keyed both ways: Delete Key removes whichever of its keys sit at this frame.
    const bool lattice = scene_.widgets.type(widget) == widgets::WidgetType::Lattice;
    for (ChannelKind k : lattice ? scenes::keyableKinds(scene_.widgets, widget) : std::vector<ChannelKind>{kind}) {
      if (auto removed = scenes::removeKey(scene_, widget, k, time))
        changes.push_back(KeyChange{widget, k, time, std::move(removed), std::nullopt});
    }
  }
  if (changes.empty()) throw std::invalid_argument("Delete Key: the selection has no key at frame " + std::to_string(frame()));
  const int count = static_cast<int>(changes.size());
  push("Delete Key", std::move(changes), animatedBefore);
  return count;
}

std::size_t Timeline::bytesOf(const std::vector<Keyframe>& keys) {
  std::size_t bytes = 0;
  for (const Keyframe& k : keys) bytes += sizeof(Keyframe) + sizeof(double) * std::size_t(k.points.size());
  return bytes;
}

void Timeline::push(const std::string& description, std::vector<KeyChange> changes,
                    const widgets::WidgetModelState& animatedBefore) {
  std::vector<Keyframe> held;
  for (const KeyChange& c : changes) {
    if (c.before) held.push_back(*c.before);
    if (c.after) held.push_back(*c.after);
  }
  // A key changes no value, but every frame change since applies the animation with it: a keyed
  // channel sets its widget, and the pose shown is the one that key made. Its undo or redo after
  // a frame change therefore runs as at the key's frame and carries the result to the frame shown,
  // as every edit does (scenes::restoreAtEditValues): the animated channels' values before and
  // after the key command (with and without the channels it made or removed) are kept for that.
  auto animated = std::make_shared<const scenes::StateDelta>(scenes::StateDelta{animatedBefore, scenes::animatedState(scene_)});
  const std::size_t bytes = sizeof(KeyChange) * changes.size() + bytesOf(held) + animated->bytes();
  auto shared = std::make_shared<const std::vector<KeyChange>>(std::move(changes));
  const std::uint64_t madeAt = controller_.animationApplications();
  auto carried = std::make_shared<std::optional<scenes::CarriedStep>>();  // makes an undo's redo exact
  auto apply = [this, shared, animated, madeAt, carried](bool forward) {
    scenes::restoreAtEditValues(scene_, forward ? animated->before : animated->after,
                                controller_.animationAppliedSince(madeAt), [&] {
                                  for (const KeyChange& c : *shared) {
                                    const std::optional<Keyframe>& to = forward ? c.after : c.before;
                                    if (to) {
                                      scenes::setKey(scene_, c.widget, c.kind, *to);
                                    } else {
                                      scenes::removeKey(scene_, c.widget, c.kind, c.time);
                                    }
                                  }
                                }, carried.get());
    controller_.refresh();  // the timeline redraws its marks (and the objects, if the pose moved)
  };
  commands_.push(scenes::Command{description, [apply] { apply(false); }, [apply] { apply(true); }, {}, bytes});
  controller_.refresh();
}

void Timeline::setPlaying(bool playing) {
  playing_ = playing;
  clock_ = frame();
}

bool Timeline::advance(double seconds) {
  if (!playing_ || !(seconds >= 0.0)) return false;
  return moveClock(seconds * scene_.animation().framesPerSecond);
}

bool Timeline::advanceFrames(int frames) {
  if (!playing_ || frames < 1) return false;
  return moveClock(frames);
}

bool Timeline::moveClock(double frames) {
  const scenes::Animation& a = scene_.animation();
  const double length = a.lastFrame - a.firstFrame + 1;  // frames shown per loop
  clock_ += frames;
  if (clock_ >= a.lastFrame + 1) clock_ = a.firstFrame + std::fmod(clock_ - a.firstFrame, length);
  if (clock_ < a.firstFrame) clock_ = a.firstFrame;
  const int whole = static_cast<int>(std::floor(clock_));
  if (whole == frame()) return false;
  // A drag under way owns the model: the clock runs on, the frame follows after the release.
  if (scene_.widgets.gestureActive() || controller_.dragging()) return false;
  frame_ = whole;
  controller_.animationApplied(scenes::frameTime(scene_.animation(), frame_));
  scenes::applyAnimationFrame(scene_, frame_);
  controller_.refresh();
  return true;
}

}  // namespace ffdkit::app
