#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "args.h"
#include "read_options.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::cli {

/// One subcommand: its name, a one-line summary, its usage and options (for --help), and what
/// it does. `run` returns the exit code (0 ok, 1 failure) and throws UsageError for exit 2.
struct Command {
  std::string name;
  std::string summary;
  std::string usage;        ///< "ffdkit-cli deform ..." lines
  std::string description;  ///< paragraphs after the usage
  std::vector<OptionSpec> options;
  int (*run)(const Args& args);
};

Command deformCommand();
Command renderCommand();
Command infoCommand();
Command validateCommand();
Command plotCommand();
Command exportCommand();

/// Runs ffdkit-cli: `argv` without the program name. Prints help and errors; returns the exit code.
int runCli(const std::vector<std::string>& argv);

/// What a file given to info / validate / deform is.
enum class FileKind { Scene, Widgets, Mesh };
/// By extension and, for .json, by its "format" member (a folder is a sample-scene folder).
FileKind fileKind(const std::filesystem::path& path);

/// Options every command has.
OptionSpec quietOption();
OptionSpec progressOption();
OptionSpec timingsOption();
OptionSpec setOption();

/// A parsed `--set NAME=VALUE`.
struct VariationSetting {
  std::string widget;
  double value = 0.0;
};
/// @throws UsageError for text that is not NAME=NUMBER.
std::vector<VariationSetting> parseSettings(const std::vector<std::string>& texts);
/// Sets each affine widget's variation through WidgetModel::setVariation (bindings follow), in
/// order. @throws std::runtime_error for an unknown name (listing the affine widgets) or a
/// widget that is not an affine widget.
void applySettings(widgets::WidgetModel& model, const std::vector<VariationSetting>& settings);

}  // namespace ffdkit::cli
