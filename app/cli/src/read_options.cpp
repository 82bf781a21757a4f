#include "read_options.h"

#include <stdexcept>
#include <string>

#include "ffdkit/meshio/mesh_io.h"
#include "ffdkit/scenes/scene_file.h"
#include "ffdkit/scenes/widget_file.h"

namespace ffdkit::cli {

namespace {

// The defaults as the help text shows them.
std::string defaultMemoryText() { return meshio::byteSizeText(meshio::ReadLimits{}.maxMemoryBytes); }
std::string defaultPointsText() { return std::to_string(meshio::ReadLimits{}.maxPoints); }

template <class Parse>
std::uint64_t parsedOption(const Args& args, const std::string& name, std::uint64_t fallback, Parse parse) {
  const auto text = args.value(name);
  if (!text) return fallback;
  try {
    return parse(*text);
  } catch (const std::invalid_argument& e) {
    throw UsageError("--" + name + ": " + e.what());
  }
}

}  // namespace

std::vector<OptionSpec> readOptions() {
  return {{"max-memory", '\0', "SIZE",
           "refuse a read that would allocate more than SIZE (e.g. 512M, 8GiB; default " + defaultMemoryText() + ")"},
          {"max-points", '\0', "N",
           "refuse a read that would produce more than N points (e.g. 2M, 100000; default " + defaultPointsText() + ")"},
          {"allow-outside", '\0', "",
           "let a file name files outside its own folder (meshes and widget files of a scene, glTF buffers)"},
          {"allow-outside-meshes", '\0', "", "the older name of --allow-outside (same effect)"}};
}

std::vector<OptionSpec> withReadOptions(std::vector<OptionSpec> options) {
  for (OptionSpec& spec : readOptions()) options.push_back(std::move(spec));
  return options;
}

ReadSettings readSettings(const Args& args) {
  ReadSettings settings;
  settings.limits.maxMemoryBytes =
      parsedOption(args, "max-memory", settings.limits.maxMemoryBytes, [](const std::string& t) { return meshio::parseByteSize(t); });
  settings.limits.maxPoints =
      parsedOption(args, "max-points", settings.limits.maxPoints, [](const std::string& t) { return meshio::parseCount(t); });
  settings.confinement.allowOutside = args.flag("allow-outside") || args.flag("allow-outside-meshes");
  return settings;
}

scenes::Scene readSceneFile(const std::filesystem::path& path, const ReadSettings& settings) {
  scenes::SceneReadOptions options;
  options.confinement = settings.confinement;
  options.limits = settings.limits;
  return scenes::readScene(path, options);
}

meshio::MeshData readMeshFile(const std::filesystem::path& path, const ReadSettings& settings) {
  meshio::MeshReadOptions options;
  options.limits = settings.limits;
  options.confinement = settings.confinement;
  return meshio::readMesh(path, options);
}

widgets::WidgetModel readWidgetsFile(const std::filesystem::path& path, const ReadSettings& settings) {
  scenes::WidgetReadOptions options;
  options.limits = settings.limits;
  return scenes::readWidgetFile(path, options);
}

}  // namespace ffdkit::cli
