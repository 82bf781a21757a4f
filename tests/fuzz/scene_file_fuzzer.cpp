// Fuzz target: the scene-file reader (objects, primitives, generators, widgets, attachments,
// animation) and the evaluation of what it read at the ends of the frame range and at its first
// keys. Reads against a small budget (SceneReadOptions::limits), so that a primitive, generator
// or lattice that a few bytes make big is refused before it is computed: what matters here is
// every path through the reader, at over a thousand inputs a second, not how a big scene
// deforms. Mesh paths resolve against a folder that does not exist, under the default
// confinement rule, so no file outside the input is read.
#include <algorithm>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/scene_file.h"

namespace {

// The keys evaluated per input: a scene with thousands of keys costs no more than one with eight.
constexpr std::size_t kKeysEvaluated = 8;

ffdkit::scenes::SceneReadOptions smallRead() {
  ffdkit::scenes::SceneReadOptions options;
  options.baseDirectory = "/nonexistent-ffdkit-fuzz-folder";
  options.limits.maxPoints = 20'000;
  options.limits.maxMemoryBytes = 16u << 20;
  return options;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const ffdkit::scenes::SceneReadOptions options = smallRead();
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    ffdkit::scenes::Scene scene = ffdkit::scenes::readScene(in, "fuzz", options);
    ffdkit::scenes::applyAnimationFrame(scene, scene.animation().firstFrame);
    const std::vector<double> keys = ffdkit::scenes::keyTimes(scene);
    for (std::size_t k = 0; k < std::min(keys.size(), kKeysEvaluated); ++k) ffdkit::scenes::applyAnimation(scene, keys[k]);
    ffdkit::scenes::applyAnimationFrame(scene, scene.animation().lastFrame);
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
