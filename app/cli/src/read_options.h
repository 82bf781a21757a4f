#pragma once
// The options of every command that reads a scene, a widget file or a mesh: the read budget
// (--max-memory, --max-points; meshio/read_limits.h) and the confinement rule (--allow-outside;
// meshio/path_confinement.h). Every read of the CLI goes through ReadSettings.

#include <filesystem>
#include <vector>

#include "args.h"
#include "ffdkit/meshio/mesh_data.h"
#include "ffdkit/meshio/path_confinement.h"
#include "ffdkit/meshio/read_limits.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::cli {

/// --max-memory SIZE, --max-points N, --allow-outside and its older name --allow-outside-meshes.
std::vector<OptionSpec> readOptions();
/// `options` followed by readOptions().
std::vector<OptionSpec> withReadOptions(std::vector<OptionSpec> options);

/// What the read options of a command line say: each read's limits and the confinement rule.
struct ReadSettings {
  meshio::ReadLimits limits{};            ///< the defaults unless --max-memory / --max-points
  meshio::PathConfinement confinement{};  ///< allowOutside with --allow-outside(-meshes)
};

/// @throws UsageError naming the option for a malformed --max-memory or --max-points value.
ReadSettings readSettings(const Args& args);

/// A scene file or sample-scene folder, read with the settings (one budget for the whole scene).
scenes::Scene readSceneFile(const std::filesystem::path& path, const ReadSettings& settings);
/// A mesh or point file, read with the settings' limits (and confinement for files it names).
meshio::MeshData readMeshFile(const std::filesystem::path& path, const ReadSettings& settings);
/// A widget file, read with the settings' limits.
widgets::WidgetModel readWidgetsFile(const std::filesystem::path& path, const ReadSettings& settings);

}  // namespace ffdkit::cli
