// ffdkit::exporters from an installed package: the installed press scene exported as one frame
// of binary glTF holds every point of every object, and the bytes are a .glb (magic "glTF",
// version 2, the length in the header equal to the bytes written).
// Usage: consumer <prefix>/share/ffdkit.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "../consumer_check.h"
#include "ffdkit/exporters/gltf_export.h"
#include "ffdkit/scenes/scene_file.h"

using namespace ffdkit;

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const scenes::Scene press = scenes::readScene(std::filesystem::path(argv[1]) / "scenes/press/scene.json");
  Eigen::Index points = 0;
  for (const auto& object : press.objects()) points += object.mesh.points.rows();
  std::ostringstream out;
  const exporters::GltfExportReport report = exporters::exportGltf(press, exporters::AnimationSource{}, out);
  const std::string bytes = out.str();
  std::uint32_t header[3] = {0, 0, 0};
  if (bytes.size() >= sizeof header) std::memcpy(header, bytes.data(), sizeof header);
  consumer::check(bytes.compare(0, 4, "glTF") == 0 && header[1] == 2 && header[2] == bytes.size(), "a .glb header");
  consumer::check(points > 0 && report.vertices == points, "every point of the scene is exported");
  return consumer::exitCode();
}
