#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "commands.h"
#include "ffdkit/scenes/scene_file.h"

namespace ffdkit::cli {

namespace {

const std::vector<Command>& commands() {
  static const std::vector<Command> list = {deformCommand(), renderCommand(), infoCommand(), validateCommand(),
                                            plotCommand(), exportCommand()};
  return list;
}

void printHelp(std::FILE* to) {
  std::fprintf(to,
               "usage: ffdkit-cli COMMAND [OPTIONS] [ARGS...]   (ffdkit-cli COMMAND --help for details)\n\n"
               "commands:\n");
  for (const auto& c : commands()) std::fprintf(to, "  %-10s %s\n", c.name.c_str(), c.summary.c_str());
  std::fprintf(to, "\nexit status: 0 success, 1 failure, 2 usage error\n");
}

void printCommandHelp(const Command& c) {
  std::printf("usage: %s\n\n%s\n\n%s\noptions:\n%s", c.usage.c_str(), c.summary.c_str(), c.description.c_str(),
              optionHelp(c.options).c_str());
}

std::string lowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return ext;
}

}  // namespace

int runCli(const std::vector<std::string>& argv) {
  if (argv.empty()) {
    printHelp(stderr);
    return 2;
  }
  if (argv[0] == "--help" || argv[0] == "-h" || argv[0] == "help") {
    printHelp(stdout);
    return 0;
  }
  for (const auto& command : commands()) {
    if (argv[0] != command.name) continue;
    const std::vector<std::string> rest(argv.begin() + 1, argv.end());
    for (const auto& arg : rest) {
      if (arg == "--") break;
      if (arg == "--help" || arg == "-h") {
        printCommandHelp(command);
        return 0;
      }
    }
    try {
      const Args args(command.options, rest);
      return command.run(args);
    } catch (const UsageError& e) {
      std::fflush(stdout);
      std::fprintf(stderr, "ffdkit-cli %s: %s\nusage: %s\n(ffdkit-cli %s --help for details)\n", command.name.c_str(),
                   e.what(), command.usage.c_str(), command.name.c_str());
      return 2;
    } catch (const std::exception& e) {
      std::fflush(stdout);
      std::fprintf(stderr, "ffdkit-cli %s: error: %s\n", command.name.c_str(), e.what());
      return 1;
    }
  }
  std::fprintf(stderr, "ffdkit-cli: unknown command '%s'\n\n", argv[0].c_str());
  printHelp(stderr);
  return 2;
}

FileKind fileKind(const std::filesystem::path& path) {
  if (std::filesystem::is_directory(path)) return FileKind::Scene;
  if (lowerExtension(path) != ".json") return FileKind::Mesh;
  // The "format" member comes first in files we write; look at the head of the text only, so
  // that a malformed file still gets its kind (and the reader reports line and column).
  std::ifstream in(path, std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  const auto widgets = head.find("\"ffdkit-widgets\"");
  const auto scene = head.find("\"ffdkit-scene\"");
  if (widgets != std::string::npos && (scene == std::string::npos || widgets < scene)) return FileKind::Widgets;
  return FileKind::Scene;
}

OptionSpec quietOption() { return {"quiet", 'q', "", "print nothing but errors and warnings"}; }
OptionSpec progressOption() {
  return {"progress", '\0', "", "show progress of long steps on stderr even when it is not a terminal"};
}
OptionSpec timingsOption() {
  return {"timings", '\0', "", "print the time split (read / build scene / embed / deform / write) in ms"};
}
OptionSpec setOption() {
  return {"set", '\0', "NAME=VALUE",
          "set the variation of affine widget NAME (distance, radians or log scale) before evaluating", true};
}

}  // namespace ffdkit::cli
