#pragma once

#include <filesystem>
#include <iosfwd>
#include <stdexcept>
#include <string>

#include "ffdkit/scenes/scene.h"

namespace ffdkit::scenes {

/// The scene file format this build reads and writes (docs/scene-file-format.md).
inline constexpr int kSceneFormatVersion = 1;

/// A scene file that cannot be read. what() says where: `scene.json:14:9: ...` for syntax
/// errors, `scene.json /objects/2/primitive/kind: unknown primitive 'teapot' (known: ...)`
/// for content errors.
class SceneFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Reads a scene from JSON text. `sourceName` names the text in error messages.
/// @throws SceneFileError on malformed JSON, an unknown or future format version, unknown
///         names, out-of-range values; nothing is returned half-read.
Scene readScene(std::istream& in, const std::string& sourceName = "<stream>");

/// Reads `path`, or `path/scene.json` when `path` is a directory (sample scenes are folders).
Scene readScene(const std::filesystem::path& path);

/// Writes the scene as JSON (stable key order, 2-space indent, trailing newline), so that
/// reading then writing gives the same bytes.
void writeScene(std::ostream& out, const Scene& scene);

/// Writes atomically: to a temporary file beside `path`, then renamed over it, so that a
/// failure never leaves a truncated or damaged file.
/// @throws SceneFileError if the file cannot be written.
void writeScene(const std::filesystem::path& path, const Scene& scene);

}  // namespace ffdkit::scenes
