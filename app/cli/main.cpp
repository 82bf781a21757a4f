// ffdkit-cli: scripted, batch use of ffdkit. Exit codes: 0 success, 1 failure, 2 usage error.
#include <cstdio>
#include <cstring>
#include <exception>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "ffdkit/app/offscreen_render.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/scene_file.h"

namespace {

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Command {
  const char* name;
  const char* summary;
  const char* usage;
  std::function<int(const std::vector<std::string>&)> run;
};

int info(const std::vector<std::string>& args) {
  if (args.size() != 1) throw UsageError("info takes one scene file");
  const auto scene = ffdkit::scenes::readScene(std::filesystem::path(args[0]));
  std::printf("scene: %s\n", args[0].c_str());
  if (!scene.description.empty()) std::printf("description: %s\n", scene.description.c_str());
  for (const auto& object : scene.objects) {
    std::printf("object %s: %lld points, %lld triangles, %lld segments\n", object.name.c_str(),
                static_cast<long long>(object.mesh.points.rows()), static_cast<long long>(object.mesh.triangles.rows()),
                static_cast<long long>(object.mesh.segments.rows()));
  }
  for (auto lattice : scene.widgets.widgets(ffdkit::widgets::WidgetType::Lattice)) {
    const Eigen::Vector3i n = scene.widgets.counts(lattice);
    std::printf("lattice %s: %dx%dx%d control points\n", scene.widgets.name(lattice).c_str(), n.x(), n.y(), n.z());
  }
  ffdkit::scenes::SceneDeformer deformer;
  deformer.update(scene);
  const auto& stats = deformer.lastStats();
  std::printf("deformed %lld points in %.1f ms (%lld outside their lattice, %lld failed to embed)\n",
              static_cast<long long>(stats.deformedPoints), 1e3 * stats.seconds,
              static_cast<long long>(stats.outsidePoints), static_cast<long long>(stats.failedPoints));
  return 0;
}

int validate(const std::vector<std::string>& args) {
  if (args.empty()) throw UsageError("validate takes one or more scene files");
  int failures = 0;
  for (const auto& path : args) {
    try {
      ffdkit::scenes::readScene(std::filesystem::path(path));
      std::printf("%s: ok\n", path.c_str());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s\n", e.what());
      ++failures;
    }
  }
  return failures == 0 ? 0 : 1;
}

int render(const std::vector<std::string>& args) {
  ffdkit::app::OffscreenRenderOptions options;
  std::vector<std::string> positional;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--size") {
      if (i + 1 >= args.size() || std::sscanf(args[i + 1].c_str(), "%dx%d", &options.width, &options.height) != 2)
        throw UsageError("--size takes WIDTHxHEIGHT, e.g. --size 800x600");
      ++i;
    } else {
      positional.push_back(args[i]);
    }
  }
  if (positional.size() != 2) throw UsageError("render takes a scene file and an output PNG");
  const auto scene = ffdkit::scenes::readScene(std::filesystem::path(positional[0]));
  ffdkit::app::renderSceneToPng(scene, positional[1], options);
  std::printf("wrote %s\n", positional[1].c_str());
  return 0;
}

const std::vector<Command>& commands() {
  static const std::vector<Command> list = {
      {"info", "summarise a scene file", "ffdkit-cli info SCENE", info},
      {"validate", "check scene files, report every error", "ffdkit-cli validate SCENE...", validate},
      {"render", "render a scene to PNG off screen", "ffdkit-cli render SCENE OUT.png [--size WxH]", render},
  };
  return list;
}

void printHelp() {
  std::printf("usage: ffdkit-cli COMMAND [ARGS...]   (ffdkit-cli COMMAND --help for details)\n\ncommands:\n");
  for (const auto& c : commands()) std::printf("  %-10s %s\n", c.name, c.summary);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0) {
    printHelp();
    return argc < 2 ? 2 : 0;
  }
  const std::string_view name = argv[1];
  for (const auto& command : commands()) {
    if (name != command.name) continue;
    std::vector<std::string> args(argv + 2, argv + argc);
    if (!args.empty() && (args[0] == "--help" || args[0] == "-h")) {
      std::printf("usage: %s\n%s\n", command.usage, command.summary);
      return 0;
    }
    try {
      return command.run(args);
    } catch (const UsageError& e) {
      std::fprintf(stderr, "ffdkit-cli %s: %s\nusage: %s\n", command.name, e.what(), command.usage);
      return 2;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "ffdkit-cli %s: %s\n", command.name, e.what());
      return 1;
    }
  }
  std::fprintf(stderr, "ffdkit-cli: unknown command '%s'\n", argv[1]);
  printHelp();
  return 2;
}
