// Fuzz target: the scene-file reader (objects, generators, widgets, attachments). Mesh paths
// resolve against a folder that does not exist, so no file outside the input is read.
#include <cstdint>
#include <sstream>
#include <string>

#include "ffdkit/scenes/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  ffdkit::scenes::SceneReadOptions options;
  options.baseDirectory = "/nonexistent-ffdkit-fuzz-folder";
  try {
    (void)ffdkit::scenes::readScene(in, "fuzz", options);
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
