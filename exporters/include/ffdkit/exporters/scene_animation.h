#pragma once

#include "ffdkit/exporters/gltf_export.h"
#include "ffdkit/scenes/scene.h"

namespace ffdkit::exporters {

/// The animation a scene's keys describe, for exportGltf: the key times of every channel, per key
/// the interpolation of the segment that starts there (Constant when every channel holds over it,
/// Smooth when any channel is Smooth, else Linear) and whether a Constant channel jumps at its
/// end, the scene's frame rate, and setTime = the scene's own evaluation (scenes::applyAnimation).
/// A scene without keys gives an empty source (a static scene).
AnimationSource sceneAnimation(const scenes::Scene& scene);

}  // namespace ffdkit::exporters
