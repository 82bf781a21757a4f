#pragma once

#include <filesystem>
#include <iosfwd>
#include <stdexcept>
#include <string>

#include "ffdkit/meshio/path_confinement.h"
#include "ffdkit/meshio/read_limits.h"
#include "ffdkit/scenes/generator.h"
#include "ffdkit/scenes/scene.h"

namespace ffdkit::scenes {

/// The scene file format this build writes (docs/scene-file-format.md). It reads every version
/// from 1: version 2 added "animation" (keys, frame rate, frame range); a version-1 file reads as
/// a version-2 file without keys.
inline constexpr int kSceneFormatVersion = 2;

/// A scene file that cannot be read. what() says where: `scene.json:14:9: ...` for syntax
/// errors, `scene.json /objects/2/primitive/kind: unknown primitive 'teapot' (known: ...)`
/// for content errors, and names a missing mesh file with the scene that references it.
class SceneFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Options of readScene: where relative paths resolve, the generators, the path rule and the read budget.
struct SceneReadOptions {
  /// Folder that relative mesh and widget-file paths resolve against (readScene(path) uses
  /// the scene file's folder).
  std::filesystem::path baseDirectory = ".";
  const GeneratorRegistry* generators = nullptr;  ///< nullptr: builtinGenerators()
  /// The one rule for every path the scene names (mesh files, its widget file, and what those
  /// name in turn): by default a path that leads outside `baseDirectory` (absolute, "..", or
  /// through a symbolic link) is an error, so a shared scene cannot make a batch job read other
  /// files (meshio/path_confinement.h).
  meshio::PathConfinement confinement{};
  /// The budget of the whole scene: every mesh file, primitive, generator and lattice together
  /// (meshio/read_limits.h). Over it, a SceneFileError names the object and what.
  meshio::ReadLimits limits{};
};

/// Reads a scene from JSON text; builds every object's points (primitives, mesh files,
/// generators) and the widget model. `sourceName` names the text in error messages.
/// @throws SceneFileError; nothing is returned half-read.
Scene readScene(std::istream& in, const std::string& sourceName = "<stream>", const SceneReadOptions& options = {});

/// Reads `path`, or `path/scene.json` when `path` is a directory (sample scenes are folders);
/// relative paths resolve against the scene file's folder (options.baseDirectory is set to it).
Scene readScene(const std::filesystem::path& path);
Scene readScene(const std::filesystem::path& path, SceneReadOptions options);

/// The canonical JSON text of a scene: fixed key order, 2-space indent, short arrays on one
/// line, shortest round-trip numbers, trailing newline; reading it and writing again gives
/// the same bytes. Widgets are inline unless `scene.widgetFile` is set.
std::string sceneFileText(const Scene& scene);
void writeScene(std::ostream& out, const Scene& scene);

/// Options of writeScene.
struct SceneWriteOptions {
  /// The reader's rule for the paths a scene names (SceneReadOptions::confinement), applied
  /// before anything is written: by default a mesh path or widget file that leads outside the
  /// folder of the file written is an error, so ffdkit never writes a scene its reader refuses
  /// by default, nor a widget file outside that folder. The app passes its preference.
  meshio::PathConfinement confinement{};
};

/// Writes atomically (temporary file + rename); when `scene.widgetFile` is set, also writes
/// that widget file (resolved against the scene file's folder), atomically. Every mesh path and
/// the widget file are checked against `options.confinement` first.
/// @throws SceneFileError if a file cannot be written, or naming the object, its JSON pointer
///   and the path that leads outside the folder (nothing is written then):
///   `out/scene.json /objects/1/mesh/path: object 'bunny': mesh file '/data/bunny.obj' is outside
///   the folder of the file that names it (...)`.
void writeScene(const std::filesystem::path& path, const Scene& scene, const SceneWriteOptions& options);
/// writeScene(path, scene, {}): paths outside the folder are refused.
void writeScene(const std::filesystem::path& path, const Scene& scene);

/// Reads a JSON object of generator parameters, the same as a scene file's generator
/// "parameters" (flags, numbers, strings, lists of numbers, lists of rows of numbers).
/// @throws SceneFileError with `file:line:column` for syntax errors and a JSON pointer for values.
GeneratorParameters readGeneratorParameters(std::istream& in, const std::string& sourceName = "<stream>");
GeneratorParameters readGeneratorParameters(const std::filesystem::path& path);

}  // namespace ffdkit::scenes
