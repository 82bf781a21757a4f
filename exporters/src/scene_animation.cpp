#include "ffdkit/exporters/scene_animation.h"

namespace ffdkit::exporters {

AnimationSource sceneAnimation(const scenes::Scene&) { return {}; }

double sceneFrameTime(const scenes::Scene&, double frame) { return frame / 24.0; }

}  // namespace ffdkit::exporters
