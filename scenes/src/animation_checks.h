#pragma once
// Private to scenes: the checks animation.cpp and the scene-file reader share.

#include <string>

#include "ffdkit/scenes/keyframes.h"
#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::scenes::detail {

/// @throws AnimationError unless `widget` exists and can be keyed by `kind` (keyableKinds).
void checkKeyable(const widgets::WidgetModel& model, widgets::WidgetId widget, ChannelKind kind);
/// What is wrong with one key of that channel ("" if nothing): time, value, shape.
std::string keyProblem(const widgets::WidgetModel& model, widgets::WidgetId widget, ChannelKind kind, const Keyframe& key);
/// A whole channel: keyable, at least one key, the limit, every key, times strictly increasing.
/// @throws AnimationError naming the channel and the key.
void checkChannel(const widgets::WidgetModel& model, const Channel& channel);

}  // namespace ffdkit::scenes::detail
