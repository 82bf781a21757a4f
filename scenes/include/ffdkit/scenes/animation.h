#pragma once

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/scenes/keyframes.h"
#include "ffdkit/scenes/scene.h"

namespace ffdkit::scenes {

/// A key or an animation that cannot be set, read or evaluated: what() names the widget, the
/// channel and the key ("channel 'knob' variation, key 3: times must increase (1.5 after 2)").
class AnimationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// "constant" / "linear" / "smooth"; "variation" / "frame" / "controlPoints" (the scene file's words).
std::string_view interpolationName(Interpolation interpolation);
std::optional<Interpolation> parseInterpolation(std::string_view name);
std::string_view channelKindName(ChannelKind kind);
std::optional<ChannelKind> parseChannelKind(std::string_view name);

/// Seconds of frame `frame` (frame / framesPerSecond) and the (fractional) frame at `seconds`.
double frameTime(const Animation& animation, double frame);
double timeFrame(const Animation& animation, double seconds);

// ---- evaluation ----------------------------------------------------------------------------------

/// The cubic Hermite value of an Interpolation::Smooth segment between keys (t0, p0) and (t1, p1)
/// with slopes m0, m1 (value per second), at t in [t0, t1]: with s = (t - t0) / h, h = t1 - t0,
///   p = (2s^3 - 3s^2 + 1) p0 + (s^3 - 2s^2 + s) h m0 + (-2s^3 + 3s^2) p1 + (s^3 - s^2) h m1.
double hermite(double t0, double p0, double m0, double t1, double p1, double m1, double t);

/// The automatic slope at key i of the samples (times[i], values[i]) (Interpolation::Smooth):
/// (values[i+1] - values[i-1]) / (times[i+1] - times[i-1]) (Catmull-Rom), 0 at the first and the
/// last key and where values[i] is a local extremum (both neighbours on one side, or equal):
/// Blender's Auto Clamped handles.
double autoSlope(const std::vector<double>& times, const std::vector<double>& values, std::size_t i);

/// A scalar channel's value at `seconds`: the keys' `variation` values, interpolated per key.
/// Before the first key: the first key's value; after the last: the last's. @throws AnimationError
/// for no keys or a non-finite time.
double evaluateVariation(const std::vector<Keyframe>& keys, double seconds);
/// A lattice-frame channel's value: translation and the symmetric stretch of the polar
/// decomposition (frame.linear() = R S) per component as a scalar channel; the rotation R as a
/// unit quaternion (signs made consistent key to key): Constant holds, Linear slerps, Smooth
/// runs the scalar rule on the four components and normalises. At a key time: the key's frame
/// exactly.
Eigen::Affine3d evaluateFrame(const std::vector<Keyframe>& keys, double seconds);
/// A control-point channel's value: every coordinate as a scalar channel. At a key time: the key's
/// points exactly.
Eigen::MatrixX3d evaluatePoints(const std::vector<Keyframe>& keys, double seconds);

/// The values of the scene's animated channels at `seconds` (keyed channels of widgets the model
/// holds, of a kind the widget can be keyed with): lattice frames, variations and control points,
/// in the animation's channel order. @throws AnimationError for a non-finite time.
widgets::WidgetModelState animationValues(const Scene& scene, double seconds);
/// The items of `state` (captured from the scene's model) that are animated channels of the scene:
/// the part of a state that applyAnimation would set.
widgets::WidgetModelState animatedPart(const Scene& scene, const widgets::WidgetModelState& state);
/// animatedPart of the model's present state.
widgets::WidgetModelState animatedState(const Scene& scene);

/// Sets the widget model's animated channels to `values` (animationValues, animatedPart) through
/// the model's own gestures, so bindings propagate exactly as during a drag:
///  1. lattice frames, parents before children (WidgetModel::pipelineOrder): a lattice gesture
///     with the world motion target * current^-1 (WidgetModel::applyMotion);
///  2. variations: those from the last down to the first whose value changes go back to 0, then
///     each, in their order, to its target: WidgetModel::setVariation (gestures; bound widgets
///     follow). A frame then gives the same model from whatever frame the model comes, even
///     where one keyed motion turns another's direction;
///  3. control points: WidgetModel::setControlPoints; they come last, so a lattice whose points
///     are keyed shows exactly those points whatever its widgets did.
/// A value already there (frames within 1e-12 relative) is not touched (no revision, nothing
/// re-deformed); values of widgets the model does not hold, or cannot reach that way, are
/// skipped. Motions that do not commute (two rotations on overlapping cells, a keyed widget
/// bound to another keyed widget) make the result depend on the state it starts from, as with
/// drags; key one widget of a bound group.
/// @throws AnimationError during a gesture; the model's WidgetError unchanged (the model keeps
///   the values applied before it).
void applyAnimatedValues(Scene& scene, const widgets::WidgetModelState& values);

/// Sets the scene's widget model to its animation at `seconds`:
/// applyAnimatedValues(scene, animationValues(scene, seconds)).
/// @throws AnimationError for a non-finite time or during a gesture; the model's WidgetError.
void applyAnimation(Scene& scene, double seconds);

/// What one command's last carried undo or redo (restoreAtEditValues after a frame change) did:
/// the model's state (WidgetModel::captureState) before and after it.
struct CarriedStep {
  widgets::WidgetModelState before;  ///< the state the carried step started from
  widgets::WidgetModelState after;   ///< the state it left
};

/// Undo and redo of an edit after frame changes. An edit's command writes back values captured
/// when the edit was made (control points, frames, variations, records); a frame change since
/// then has moved the model by the animation (keyed channels to their keys, bound widgets with
/// them), so writing the old values alone would mix two frames. This runs `restore` (the
/// command's write-back) as at the edit, then carries the result to the time shown:
///  1. the animated channels are set to `editValues` (applyAnimatedValues): their values when
///     the edit ended, for an undo, or when it started, for a redo (animatedState then);
///  2. `restore()`;
///  3. the model is set to the animation at `*shownSeconds` (the time the model was last set
///     to) with the document the write-back made: applyAnimatedValues(animationValues(...)), as a
///     frame change to that time does, so such a frame change afterwards changes nothing (but
///     rounding, where a keyed widget is bound to another keyed widget).
/// `shownSeconds` is given when the animation was applied since the edit (a frame change);
/// without it only `restore()` runs, and the write-back is exact.
///
/// The carry goes through the bindings, and clamped or non-commuting ones (a keyed handle driving
/// a clamped screw, rotations on overlapping cells) do not come back by the reverse motion: an
/// undo carried and its redo carried again would not give the state before the undo. `last`, the
/// command's own record (nullptr: none), makes the inverse exact: each carried step stores the
/// model's state before and after it there, and a step that starts from exactly the state the
/// last one left (a redo right after its undo, an undo right after its redo) runs `restore()` and
/// then writes the stored state back, instead of carrying again.
void restoreAtEditValues(Scene& scene, const widgets::WidgetModelState& editValues, std::optional<double> shownSeconds,
                         const std::function<void()>& restore, std::optional<CarriedStep>* last = nullptr);
/// applyAnimation at frameTime(scene.animation(), frame).
void applyAnimationFrame(Scene& scene, double frame);

/// Every key time of the scene's animation (channels of existing widgets), sorted, unique.
std::vector<double> keyTimes(const Scene& scene);
/// The key times of the channels of `widget` (any kind), sorted, unique.
std::vector<double> keyTimes(const Scene& scene, widgets::WidgetId widget);

// ---- editing (each stamps Scene::animationRevision) --------------------------------------------

/// The channel kinds `widget` can be keyed with: an affine widget its variation; a lattice its
/// frame (unless it is a child whose two-way hierarchy binding makes it follow its parent cell)
/// and its control points.
std::vector<ChannelKind> keyableKinds(const widgets::WidgetModel& model, widgets::WidgetId widget);

/// A key of `widget`'s present value of `kind` at `seconds`.
/// @throws AnimationError if the widget cannot be keyed that way or the time is not finite.
Keyframe currentKey(const Scene& scene, widgets::WidgetId widget, ChannelKind kind, double seconds,
                    Interpolation interpolation = Interpolation::Smooth);

/// The channel of `widget` and `kind`, or nullptr.
const Channel* findChannel(const Animation& animation, widgets::WidgetId widget, ChannelKind kind);
/// The key of that channel at `seconds` (within 1e-9 s), or nullopt.
std::optional<Keyframe> keyAt(const Animation& animation, widgets::WidgetId widget, ChannelKind kind, double seconds);

/// Inserts `key` into the channel of `widget` and `kind` (made when missing, appended), replacing
/// a key at the same time (within 1e-9 s). @return the key it replaced, if any.
/// @throws AnimationError for a widget that cannot be keyed that way, a non-finite or too large
/// time, a non-finite or singular frame, points of the wrong shape or non-finite, limits.
std::optional<Keyframe> setKey(Scene& scene, widgets::WidgetId widget, ChannelKind kind, Keyframe key);
/// Removes the key at `seconds` (within 1e-9 s) of that channel; a channel left empty goes.
/// @return the key removed, or nullopt if there was none.
std::optional<Keyframe> removeKey(Scene& scene, widgets::WidgetId widget, ChannelKind kind, double seconds);

/// Checks an animation against its scene: frame rate, range, one channel per widget and kind,
/// widgets that exist and can be keyed that way, keys strictly increasing with finite times,
/// finite values of the right shape, invertible frames, the limits of keyframes.h.
/// @throws AnimationError naming the channel and key.
void validateAnimation(const Scene& scene);

}  // namespace ffdkit::scenes
