#include "ffdkit/scenes/animation.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <vector>

#include "animation_checks.h"

namespace ffdkit::scenes {
namespace {

using widgets::WidgetId;
using widgets::WidgetModel;
using widgets::WidgetType;

constexpr double kSameTime = 1e-9;  // seconds: keys this close are one key (a frame is >= 1 ms)

std::string number(double v) {
  std::ostringstream out;
  out.precision(17);
  out << v;
  return out.str();
}

std::string channelLabel(const WidgetModel& model, WidgetId widget, ChannelKind kind) {
  const std::string name = model.contains(widget) ? "'" + model.name(widget) + "'" : widgets::toString(widget);
  return "channel " + name + " " + std::string(channelKindName(kind));
}

// The segment of `keys` holding `seconds`: the index i of the last key with time <= seconds
// (-1 before the first key).
std::ptrdiff_t segmentOf(const std::vector<Keyframe>& keys, double seconds) {
  const auto it = std::upper_bound(keys.begin(), keys.end(), seconds,
                                   [](double t, const Keyframe& k) { return t < k.time; });
  return std::distance(keys.begin(), it) - 1;
}

void checkEvaluable(const std::vector<Keyframe>& keys, double seconds) {
  if (keys.empty()) throw AnimationError("a channel without keys has no value");
  if (!std::isfinite(seconds)) throw AnimationError("animation time must be finite, got " + number(seconds));
}

// Row i of `values` (one row per key, one column per scalar component) interpolated at `seconds`
// inside segment i (keys[i].time < seconds < keys[i+1].time), by keys[i]'s rule.
Eigen::RowVectorXd interpolateRows(const std::vector<Keyframe>& keys, const Eigen::MatrixXd& values, std::size_t i,
                                   double seconds) {
  const double t0 = keys[i].time, t1 = keys[i + 1].time;
  switch (keys[i].interpolation) {
    case Interpolation::Constant: return values.row(Eigen::Index(i));
    case Interpolation::Linear: {
      const double s = (seconds - t0) / (t1 - t0);
      return (1.0 - s) * values.row(Eigen::Index(i)) + s * values.row(Eigen::Index(i + 1));
    }
    case Interpolation::Smooth: break;
  }
  std::vector<double> times(keys.size());
  for (std::size_t k = 0; k < keys.size(); ++k) times[k] = keys[k].time;
  Eigen::RowVectorXd out(values.cols());
  std::vector<double> column(keys.size());
  for (Eigen::Index c = 0; c < values.cols(); ++c) {
    // Only keys i-1 .. i+2 shape the segment's tangents.
    for (std::size_t k = (i == 0 ? 0 : i - 1); k < std::min(keys.size(), i + 3); ++k) column[k] = values(Eigen::Index(k), c);
    out(c) = hermite(t0, column[i], autoSlope(times, column, i), t1, column[i + 1], autoSlope(times, column, i + 1), seconds);
  }
  return out;
}

struct FrameParts {
  Eigen::Vector3d translation;
  Eigen::Quaterniond rotation;
  Eigen::Matrix3d stretch;  // symmetric
};

FrameParts decompose(const Eigen::Affine3d& frame) {
  Eigen::Matrix3d rotation, stretch;
  frame.computeRotationScaling(&rotation, &stretch);
  return {frame.translation(), Eigen::Quaterniond(rotation), stretch};
}

bool finite(const Eigen::Affine3d& frame) { return frame.matrix().allFinite(); }

}  // namespace

// ---- names ---------------------------------------------------------------------------------------

std::string_view interpolationName(Interpolation interpolation) {
  switch (interpolation) {
    case Interpolation::Constant: return "constant";
    case Interpolation::Linear: return "linear";
    case Interpolation::Smooth: return "smooth";
  }
  return "smooth";
}

std::optional<Interpolation> parseInterpolation(std::string_view name) {
  for (Interpolation i : {Interpolation::Constant, Interpolation::Linear, Interpolation::Smooth})
    if (interpolationName(i) == name) return i;
  return std::nullopt;
}

std::string_view channelKindName(ChannelKind kind) {
  switch (kind) {
    case ChannelKind::Variation: return "variation";
    case ChannelKind::LatticeFrame: return "frame";
    case ChannelKind::ControlPoints: return "controlPoints";
  }
  return "variation";
}

std::optional<ChannelKind> parseChannelKind(std::string_view name) {
  for (ChannelKind k : {ChannelKind::Variation, ChannelKind::LatticeFrame, ChannelKind::ControlPoints})
    if (channelKindName(k) == name) return k;
  return std::nullopt;
}

double frameTime(const Animation& animation, double frame) { return frame / animation.framesPerSecond; }
double timeFrame(const Animation& animation, double seconds) { return seconds * animation.framesPerSecond; }

// ---- evaluation ----------------------------------------------------------------------------------

double hermite(double t0, double p0, double m0, double t1, double p1, double m1, double t) {
  const double h = t1 - t0;
  const double s = (t - t0) / h, s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * h * m0 + (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * h * m1;
}

double autoSlope(const std::vector<double>& times, const std::vector<double>& values, std::size_t i) {
  if (i == 0 || i + 1 >= times.size()) return 0.0;
  const double before = values[i] - values[i - 1], after = values[i + 1] - values[i];
  if (before * after <= 0.0) return 0.0;  // an extremum (or a flat side): a flat tangent, no overshoot
  return (values[i + 1] - values[i - 1]) / (times[i + 1] - times[i - 1]);
}

double evaluateVariation(const std::vector<Keyframe>& keys, double seconds) {
  checkEvaluable(keys, seconds);
  const std::ptrdiff_t i = segmentOf(keys, seconds);
  if (i < 0) return keys.front().variation;
  if (std::size_t(i) + 1 >= keys.size() || keys[std::size_t(i)].time == seconds) return keys[std::size_t(i)].variation;
  Eigen::MatrixXd values(Eigen::Index(keys.size()), 1);
  for (std::size_t k = 0; k < keys.size(); ++k) values(Eigen::Index(k), 0) = keys[k].variation;
  return interpolateRows(keys, values, std::size_t(i), seconds)(0);
}

Eigen::Affine3d evaluateFrame(const std::vector<Keyframe>& keys, double seconds) {
  checkEvaluable(keys, seconds);
  const std::ptrdiff_t signedIndex = segmentOf(keys, seconds);
  if (signedIndex < 0) return keys.front().frame;
  const auto i = std::size_t(signedIndex);
  if (i + 1 >= keys.size() || keys[i].time == seconds || keys[i].interpolation == Interpolation::Constant)
    return keys[i].frame;
  // One row per key: translation (3), rotation quaternion w x y z (4), stretch upper triangle (6).
  Eigen::MatrixXd values(Eigen::Index(keys.size()), 13);
  Eigen::Quaterniond previous = Eigen::Quaterniond::Identity();
  for (std::size_t k = 0; k < keys.size(); ++k) {
    FrameParts p = decompose(keys[k].frame);
    if (k > 0 && p.rotation.dot(previous) < 0.0) p.rotation.coeffs() = -p.rotation.coeffs();  // the short way
    previous = p.rotation;
    const auto r = Eigen::Index(k);
    values.block<1, 3>(r, 0) = p.translation.transpose();
    values.block<1, 4>(r, 3) << p.rotation.w(), p.rotation.x(), p.rotation.y(), p.rotation.z();
    values.block<1, 6>(r, 7) << p.stretch(0, 0), p.stretch(0, 1), p.stretch(0, 2), p.stretch(1, 1), p.stretch(1, 2),
        p.stretch(2, 2);
  }
  const Eigen::RowVectorXd row = interpolateRows(keys, values, i, seconds);
  Eigen::Quaterniond rotation(row(3), row(4), row(5), row(6));
  if (keys[i].interpolation == Interpolation::Linear) {
    const auto q = [&](std::size_t k) {
      return Eigen::Quaterniond(values(Eigen::Index(k), 3), values(Eigen::Index(k), 4), values(Eigen::Index(k), 5),
                                values(Eigen::Index(k), 6));
    };
    rotation = q(i).slerp((seconds - keys[i].time) / (keys[i + 1].time - keys[i].time), q(i + 1));
  }
  rotation.normalize();
  Eigen::Matrix3d stretch;
  stretch << row(7), row(8), row(9), row(8), row(10), row(11), row(9), row(11), row(12);
  Eigen::Affine3d frame = Eigen::Affine3d::Identity();
  frame.linear() = rotation.toRotationMatrix() * stretch;
  frame.translation() = row.segment<3>(0).transpose();
  return frame;
}

Eigen::MatrixX3d evaluatePoints(const std::vector<Keyframe>& keys, double seconds) {
  checkEvaluable(keys, seconds);
  const std::ptrdiff_t signedIndex = segmentOf(keys, seconds);
  if (signedIndex < 0) return keys.front().points;
  const auto i = std::size_t(signedIndex);
  if (i + 1 >= keys.size() || keys[i].time == seconds || keys[i].interpolation == Interpolation::Constant)
    return keys[i].points;
  const Eigen::Index n = keys[i].points.rows();
  Eigen::MatrixXd values(Eigen::Index(keys.size()), 3 * n);
  for (std::size_t k = 0; k < keys.size(); ++k)
    for (Eigen::Index p = 0; p < n; ++p) values.block<1, 3>(Eigen::Index(k), 3 * p) = keys[k].points.row(p);
  const Eigen::RowVectorXd row = interpolateRows(keys, values, i, seconds);
  Eigen::MatrixX3d points(n, 3);
  for (Eigen::Index p = 0; p < n; ++p) points.row(p) = row.segment<3>(3 * p);
  return points;
}

namespace {

// The scene's channels that applyAnimation sets: keyed, of a widget the model holds, of a kind
// that widget can be keyed with.
bool liveChannel(const Scene& scene, const Channel& c) {
  if (c.keys.empty() || !scene.widgets.contains(c.widget)) return false;
  const auto kinds = keyableKinds(scene.widgets, c.widget);
  return std::find(kinds.begin(), kinds.end(), c.kind) != kinds.end();
}

template <class Value>
const Value* findValue(const std::vector<std::pair<WidgetId, Value>>& items, WidgetId id) {
  const auto it = std::find_if(items.begin(), items.end(), [&](const auto& item) { return item.first == id; });
  return it == items.end() ? nullptr : &it->second;
}

// Exactly the same widgets, in the same order, with exactly the same values.
bool sameState(const widgets::WidgetModelState& a, const widgets::WidgetModelState& b) {
  const auto same = [](const auto& x, const auto& y, auto equal) {
    if (x.size() != y.size()) return false;
    for (std::size_t i = 0; i < x.size(); ++i)
      if (x[i].first != y[i].first || !equal(x[i].second, y[i].second)) return false;
    return true;
  };
  return same(a.variations, b.variations, [](double u, double v) { return u == v; }) &&
         same(a.latticeFrames, b.latticeFrames,
              [](const Eigen::Affine3d& u, const Eigen::Affine3d& v) { return u.matrix() == v.matrix(); }) &&
         same(a.controlPoints, b.controlPoints, [](const Eigen::MatrixX3d& u, const Eigen::MatrixX3d& v) {
           return u.rows() == v.rows() && u == v;
         });
}

}  // namespace

widgets::WidgetModelState animationValues(const Scene& scene, double seconds) {
  if (!std::isfinite(seconds)) throw AnimationError("animation time must be finite, got " + number(seconds));
  widgets::WidgetModelState values;
  for (const Channel& c : scene.animation().channels) {
    if (!liveChannel(scene, c)) continue;
    switch (c.kind) {
      case ChannelKind::LatticeFrame: values.latticeFrames.emplace_back(c.widget, evaluateFrame(c.keys, seconds)); break;
      case ChannelKind::Variation: values.variations.emplace_back(c.widget, evaluateVariation(c.keys, seconds)); break;
      case ChannelKind::ControlPoints: values.controlPoints.emplace_back(c.widget, evaluatePoints(c.keys, seconds)); break;
    }
  }
  return values;
}

widgets::WidgetModelState animatedPart(const Scene& scene, const widgets::WidgetModelState& state) {
  widgets::WidgetModelState part;
  for (const Channel& c : scene.animation().channels) {
    if (!liveChannel(scene, c)) continue;
    switch (c.kind) {
      case ChannelKind::LatticeFrame:
        if (const auto* v = findValue(state.latticeFrames, c.widget)) part.latticeFrames.emplace_back(c.widget, *v);
        break;
      case ChannelKind::Variation:
        if (const auto* v = findValue(state.variations, c.widget)) part.variations.emplace_back(c.widget, *v);
        break;
      case ChannelKind::ControlPoints:
        if (const auto* v = findValue(state.controlPoints, c.widget)) part.controlPoints.emplace_back(c.widget, *v);
        break;
    }
  }
  return part;
}

widgets::WidgetModelState animatedState(const Scene& scene) { return animatedPart(scene, scene.widgets.captureState()); }

void applyAnimatedValues(Scene& scene, const widgets::WidgetModelState& values) {
  WidgetModel& model = scene.widgets;
  if (model.gestureActive()) throw AnimationError("cannot evaluate the animation during a gesture");
  for (WidgetId lattice : model.pipelineOrder()) {
    const Eigen::Affine3d* target = findValue(values.latticeFrames, lattice);
    if (target == nullptr) continue;
    const auto kinds = keyableKinds(model, lattice);  // a child bound two-way cannot reach a frame
    if (std::find(kinds.begin(), kinds.end(), ChannelKind::LatticeFrame) == kinds.end()) continue;
    const Eigen::Affine3d now = model.latticeFrame(lattice);
    // A gesture leaves the frame within rounding of the target: that counts as there.
    const double scale = std::max(1.0, target->matrix().cwiseAbs().maxCoeff());
    if ((target->matrix() - now.matrix()).cwiseAbs().maxCoeff() <= 1e-12 * scale) continue;
    model.applyMotion(lattice, *target * now.inverse());
  }
  // Variations are wound in the channels' order from 0, and a change first unwinds the channels,
  // from the last down to the first whose value changes, back to 0: a motion whose direction
  // depends on another keyed channel (a push on a face whose edge a keyed pull tilts: the face's
  // fitted frame, so the push's direction, follows the pull) then gives the same model at a time
  // from whatever time the model comes, and a frame change there and back is exact. Winding
  // straight from value to value would leave such a face off by the push times the tilt.
  std::vector<std::pair<WidgetId, double>> keyed;
  for (const auto& [widget, target] : values.variations)
    if (model.contains(widget) && model.type(widget) == WidgetType::Affine) keyed.emplace_back(widget, target);
  const auto at = [&](WidgetId widget, double target) {
    return std::abs(model.variation(widget) - target) <= 1e-12 * std::max(1.0, std::abs(target));
  };
  std::size_t first = 0;
  while (first < keyed.size() && at(keyed[first].first, keyed[first].second)) ++first;
  for (std::size_t i = keyed.size(); i-- > first;)
    if (model.variation(keyed[i].first) != 0.0) model.setVariation(keyed[i].first, 0.0);
  for (std::size_t i = first; i < keyed.size(); ++i)
    if (!at(keyed[i].first, keyed[i].second)) model.setVariation(keyed[i].first, keyed[i].second);
  for (const auto& [widget, target] : values.controlPoints) {
    if (!model.contains(widget) || model.type(widget) != WidgetType::Lattice) continue;
    if (target.rows() != model.controlPoints(widget).rows() || target == model.controlPoints(widget)) continue;
    model.setControlPoints(widget, target);
  }
}

void applyAnimation(Scene& scene, double seconds) {
  applyAnimatedValues(scene, animationValues(scene, seconds));
}

void restoreAtEditValues(Scene& scene, const widgets::WidgetModelState& editValues, std::optional<double> shownSeconds,
                         const std::function<void()>& restore, std::optional<CarriedStep>* last) {
  if (!shownSeconds) {
    restore();  // the model is as the edit left it (or as its undo did): exact
    if (last != nullptr) last->reset();
    return;
  }
  widgets::WidgetModelState start = scene.widgets.captureState();
  if (last != nullptr && last->has_value() && sameState(start, (*last)->after)) {
    // The inverse of the command's last carried step, from the state it left: its records (and
    // any structure) by the write-back, then every value as it was before that step.
    widgets::WidgetModelState back = std::move((*last)->before);
    restore();
    scene.widgets.restoreState(back);
    *last = CarriedStep{std::move(start), std::move(back)};
    return;
  }
  applyAnimatedValues(scene, editValues);
  restore();
  // The time shown, as a frame change shows it with the document the write-back made (its keys,
  // bindings and widgets): a scrub to that time then changes nothing. Setting the channels back
  // to the values shown before the step instead left a pose no frame change gives where those
  // values came through a binding (a keyed widget bound to another keyed widget shows the
  // binding's value, not its key's) or from what the step undid (a key, a binding), and the next
  // frame change, even to the same frame, moved the scene and made the step's inverse carry
  // from another state.
  applyAnimatedValues(scene, animationValues(scene, *shownSeconds));
  if (last != nullptr) *last = CarriedStep{std::move(start), scene.widgets.captureState()};
}

void applyAnimationFrame(Scene& scene, double frame) { applyAnimation(scene, frameTime(scene.animation(), frame)); }

std::vector<double> keyTimes(const Scene& scene) {
  std::vector<double> times;
  for (const Channel& c : scene.animation().channels) {
    if (!scene.widgets.contains(c.widget)) continue;
    for (const Keyframe& k : c.keys) times.push_back(k.time);
  }
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  return times;
}

std::vector<double> keyTimes(const Scene& scene, WidgetId widget) {
  std::vector<double> times;
  for (const Channel& c : scene.animation().channels) {
    if (c.widget != widget) continue;
    for (const Keyframe& k : c.keys) times.push_back(k.time);
  }
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  return times;
}

// ---- editing -------------------------------------------------------------------------------------

std::vector<ChannelKind> keyableKinds(const WidgetModel& model, WidgetId widget) {
  if (!model.contains(widget)) return {};
  switch (model.type(widget)) {
    case WidgetType::Affine: return {ChannelKind::Variation};
    case WidgetType::Cell: return {};
    case WidgetType::Lattice: break;
  }
  // A child lattice bound two-way moves its parent cell when dragged (it does not move itself):
  // a keyed frame could not be reached, so only its points can be keyed.
  if (model.parentCell(widget)) {
    for (widgets::BindingId b : model.bindingsOf(widget)) {
      const widgets::Binding& binding = model.binding(b);
      if (binding.kind == widgets::BindingKind::Hierarchy && binding.to == widget && !binding.oneWay)
        return {ChannelKind::ControlPoints};
    }
  }
  return {ChannelKind::LatticeFrame, ChannelKind::ControlPoints};
}

Keyframe currentKey(const Scene& scene, WidgetId widget, ChannelKind kind, double seconds, Interpolation interpolation) {
  const WidgetModel& model = scene.widgets;
  detail::checkKeyable(model, widget, kind);
  if (!std::isfinite(seconds)) throw AnimationError("key time must be finite, got " + number(seconds));
  Keyframe key;
  key.time = seconds;
  key.interpolation = interpolation;
  switch (kind) {
    case ChannelKind::Variation: key.variation = model.variation(widget); break;
    case ChannelKind::LatticeFrame: key.frame = model.latticeFrame(widget); break;
    case ChannelKind::ControlPoints: key.points = model.controlPoints(widget); break;
  }
  return key;
}

const Channel* findChannel(const Animation& animation, WidgetId widget, ChannelKind kind) {
  for (const Channel& c : animation.channels)
    if (c.widget == widget && c.kind == kind) return &c;
  return nullptr;
}

std::optional<Keyframe> keyAt(const Animation& animation, WidgetId widget, ChannelKind kind, double seconds) {
  const Channel* c = findChannel(animation, widget, kind);
  if (c == nullptr) return std::nullopt;
  for (const Keyframe& k : c->keys)
    if (std::abs(k.time - seconds) <= kSameTime) return k;
  return std::nullopt;
}

std::optional<Keyframe> setKey(Scene& scene, WidgetId widget, ChannelKind kind, Keyframe key) {
  detail::checkKeyable(scene.widgets, widget, kind);
  if (const std::string problem = detail::keyProblem(scene.widgets, widget, kind, key); !problem.empty())
    throw AnimationError(channelLabel(scene.widgets, widget, kind) + ": " + problem);
  Animation& animation = scene.animation_;
  auto channel = std::find_if(animation.channels.begin(), animation.channels.end(),
                              [&](const Channel& c) { return c.widget == widget && c.kind == kind; });
  if (channel == animation.channels.end()) {
    if (animation.channels.size() >= kMaxChannels)
      throw AnimationError("an animation holds at most " + std::to_string(kMaxChannels) + " channels");
    animation.channels.push_back(Channel{widget, kind, {}});
    channel = std::prev(animation.channels.end());
  }
  std::optional<Keyframe> replaced;
  auto& keys = channel->keys;
  auto at = std::lower_bound(keys.begin(), keys.end(), key.time - kSameTime,
                             [](const Keyframe& k, double t) { return k.time < t; });
  if (at != keys.end() && std::abs(at->time - key.time) <= kSameTime) {
    replaced = std::move(*at);
    *at = std::move(key);
  } else {
    if (keys.size() >= kMaxKeysPerChannel)
      throw AnimationError(channelLabel(scene.widgets, widget, kind) + ": at most " + std::to_string(kMaxKeysPerChannel) +
                           " keys per channel");
    keys.insert(at, std::move(key));
  }
  scene.animationRevision_ = scene.stamp();
  return replaced;
}

std::optional<Keyframe> removeKey(Scene& scene, WidgetId widget, ChannelKind kind, double seconds) {
  Animation& animation = scene.animation_;
  auto channel = std::find_if(animation.channels.begin(), animation.channels.end(),
                              [&](const Channel& c) { return c.widget == widget && c.kind == kind; });
  if (channel == animation.channels.end()) return std::nullopt;
  auto at = std::find_if(channel->keys.begin(), channel->keys.end(),
                         [&](const Keyframe& k) { return std::abs(k.time - seconds) <= kSameTime; });
  if (at == channel->keys.end()) return std::nullopt;
  Keyframe removed = std::move(*at);
  channel->keys.erase(at);
  if (channel->keys.empty()) animation.channels.erase(channel);
  scene.animationRevision_ = scene.stamp();
  return removed;
}

void validateAnimation(const Scene& scene) {
  const Animation& a = scene.animation();
  if (!(a.framesPerSecond > 0.0 && a.framesPerSecond <= kMaxFrameRate))
    throw AnimationError("frame rate must be in (0, " + number(kMaxFrameRate) + "] frames per second, got " +
                         number(a.framesPerSecond));
  if (std::abs(a.firstFrame) > kMaxFrameMagnitude || std::abs(a.lastFrame) > kMaxFrameMagnitude)
    throw AnimationError("frames must be within +-" + std::to_string(kMaxFrameMagnitude));
  if (a.firstFrame > a.lastFrame)
    throw AnimationError("the frame range " + std::to_string(a.firstFrame) + ".." + std::to_string(a.lastFrame) +
                         " is empty (first > last)");
  if (a.channels.size() > kMaxChannels)
    throw AnimationError("an animation holds at most " + std::to_string(kMaxChannels) + " channels, got " +
                         std::to_string(a.channels.size()));
  std::size_t values = 0;
  for (std::size_t i = 0; i < a.channels.size(); ++i) {
    const Channel& c = a.channels[i];
    for (std::size_t j = 0; j < i; ++j)
      if (a.channels[j].widget == c.widget && a.channels[j].kind == c.kind)
        throw AnimationError(channelLabel(scene.widgets, c.widget, c.kind) + ": listed twice (channels " +
                             std::to_string(j) + " and " + std::to_string(i) + ")");
    detail::checkChannel(scene.widgets, c);
    for (const Keyframe& k : c.keys) values += 1 + std::size_t(k.points.size());
    if (values > kMaxKeyValues)
      throw AnimationError("the keys hold more than " + std::to_string(kMaxKeyValues) + " numbers");
  }
}

namespace detail {

void checkKeyable(const WidgetModel& model, WidgetId widget, ChannelKind kind) {
  if (!model.contains(widget)) throw AnimationError("unknown widget " + widgets::toString(widget));
  const auto kinds = keyableKinds(model, widget);
  if (std::find(kinds.begin(), kinds.end(), kind) != kinds.end()) return;
  std::string why;
  switch (model.type(widget)) {
    case WidgetType::Affine: why = "an affine widget keys its variation"; break;
    case WidgetType::Cell: why = "a cell has no keyable value (key the widgets that move it)"; break;
    case WidgetType::Lattice:
      why = kind == ChannelKind::Variation ? "a lattice keys its frame or its control points"
                                           : "it follows its parent cell through a two-way binding (key the widgets that "
                                             "move the cell, or make the binding one-way)";
      break;
  }
  throw AnimationError("widget '" + model.name(widget) + "' cannot be keyed by " + std::string(channelKindName(kind)) +
                       ": " + why);
}

std::string keyProblem(const WidgetModel& model, WidgetId widget, ChannelKind kind, const Keyframe& key) {
  if (!std::isfinite(key.time)) return "key time must be finite, got " + number(key.time);
  if (std::abs(key.time) > kMaxKeyTime) return "key time " + number(key.time) + " s is beyond +-" + number(kMaxKeyTime) + " s";
  switch (kind) {
    case ChannelKind::Variation:
      if (!std::isfinite(key.variation)) return "variation must be finite";
      break;
    case ChannelKind::LatticeFrame:
      if (!finite(key.frame) || !(std::abs(key.frame.linear().determinant()) > 1e-12))
        return "frame must be finite and invertible";
      break;
    case ChannelKind::ControlPoints: {
      const Eigen::Index expected = model.controlPoints(widget).rows();
      if (key.points.rows() != expected)
        return "expected " + std::to_string(expected) + " control points (the lattice's count), got " +
               std::to_string(key.points.rows());
      if (!key.points.allFinite()) return "control points must be finite";
      break;
    }
  }
  return {};
}

void checkChannel(const WidgetModel& model, const Channel& channel) {
  checkKeyable(model, channel.widget, channel.kind);
  const std::string label = channelLabel(model, channel.widget, channel.kind);
  if (channel.keys.empty()) throw AnimationError(label + ": a channel needs at least one key");
  if (channel.keys.size() > kMaxKeysPerChannel)
    throw AnimationError(label + ": at most " + std::to_string(kMaxKeysPerChannel) + " keys per channel, got " +
                         std::to_string(channel.keys.size()));
  for (std::size_t k = 0; k < channel.keys.size(); ++k) {
    if (const std::string problem = keyProblem(model, channel.widget, channel.kind, channel.keys[k]); !problem.empty())
      throw AnimationError(label + ", key " + std::to_string(k) + ": " + problem);
    if (k > 0 && !(channel.keys[k].time - channel.keys[k - 1].time > kSameTime))
      throw AnimationError(label + ", key " + std::to_string(k) + ": key times must increase (" +
                           number(channel.keys[k].time) + " after " + number(channel.keys[k - 1].time) + ")");
  }
}

}  // namespace detail
}  // namespace ffdkit::scenes
