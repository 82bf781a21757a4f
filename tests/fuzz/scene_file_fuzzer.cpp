// Fuzz target: the scene-file reader (objects, generators, widgets, attachments, animation) and
// the evaluation of what it read at the ends of the frame range and at every key. Mesh paths
// resolve against a folder that does not exist, so no file outside the input is read.
#include <cstdint>
#include <sstream>
#include <string>

#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  ffdkit::scenes::SceneReadOptions options;
  options.baseDirectory = "/nonexistent-ffdkit-fuzz-folder";
  try {
    ffdkit::scenes::Scene scene = ffdkit::scenes::readScene(in, "fuzz", options);
    ffdkit::scenes::applyAnimationFrame(scene, scene.animation().firstFrame);
    for (double t : ffdkit::scenes::keyTimes(scene)) ffdkit::scenes::applyAnimation(scene, t);
    ffdkit::scenes::applyAnimationFrame(scene, scene.animation().lastFrame);
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
