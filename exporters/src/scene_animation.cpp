#include "ffdkit/exporters/scene_animation.h"

#include "ffdkit/scenes/animation.h"

namespace ffdkit::exporters {

namespace {

// How the scene moves over [keyTimes[i], keyTimes[i+1]): per channel, its key in effect at the
// segment's start governs it (keys lie only at segment ends); a channel before its first or at
// its last key holds.
KeyInterpolation segmentInterpolation(const scenes::Scene& scene, double start, bool* jumps) {
  bool anyLinear = false;
  bool anySmooth = false;
  *jumps = false;
  for (const scenes::Channel& channel : scene.animation().channels) {
    if (!scene.widgets.contains(channel.widget)) continue;  // skipped by applyAnimation too
    const scenes::Keyframe* active = nullptr;
    for (const scenes::Keyframe& key : channel.keys)
      if (key.time <= start + 1e-9) active = &key;
    // Before the first key or from the last one on, the value holds.
    if (!active || active == &channel.keys.back()) continue;
    anySmooth = anySmooth || active->interpolation == scenes::Interpolation::Smooth;
    anyLinear = anyLinear || active->interpolation == scenes::Interpolation::Linear;
    *jumps = *jumps || active->interpolation == scenes::Interpolation::Constant;
  }
  return anySmooth ? KeyInterpolation::Smooth : anyLinear ? KeyInterpolation::Linear : KeyInterpolation::Constant;
}

}  // namespace

AnimationSource sceneAnimation(const scenes::Scene& scene) {
  AnimationSource source;
  source.frameRate = scene.animation().framesPerSecond;
  source.keyTimes = scenes::keyTimes(scene);
  if (source.keyTimes.empty()) return source;
  for (const double t : source.keyTimes) {
    bool jumps = false;
    source.interpolation.push_back(segmentInterpolation(scene, t, &jumps));
    source.jumps.push_back(jumps);
  }
  source.setTime = [](scenes::Scene& s, double t) { scenes::applyAnimation(s, t); };
  return source;
}

}  // namespace ffdkit::exporters
