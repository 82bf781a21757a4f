#pragma once
// One confinement rule for every path a file names: a mesh path in a scene, a scene's widget
// file, a glTF's external buffer, and whatever a format adds later. A shared file must not make
// a batch job or the app read other files: a named path is resolved against the folder of the
// file that names it, and it must stay inside that folder after "..", absolute paths and
// symbolic links are resolved. The opt-out is explicit (`--allow-outside`, the app's
// preference, PathConfinement::allowOutside).

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace ffdkit::meshio {

/// The rule for paths a file names (meshes of a scene, buffers of a glTF file, files of a polyMesh).
struct PathConfinement {
  /// false (the default): a named path that leads outside the naming file's folder is refused.
  bool allowOutside = false;
};

/// A named path that the confinement rule refuses. what() says which path, named where, and how
/// to allow it; it never quotes the contents of the file the path leads to.
class PathOutsideFolderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Whether `named` (relative to `folder`, or absolute) leads to a place inside `folder`, after
/// "..", absolute paths and symbolic links are resolved. An unresolvable path is outside.
bool isInsideFolder(const std::filesystem::path& named, const std::filesystem::path& folder);

/// The path `named` stands for (relative paths resolve against `folder`), checked by the rule.
/// `what` says what names it, for the message: "mesh file", "widget file", "external buffer".
/// @throws PathOutsideFolderError "widget file '../private/tool.json' is outside the folder of
/// the file that names it (a shared file must not read other files; allow it with
/// --allow-outside or the app's preference)".
std::filesystem::path confinedPath(const std::filesystem::path& folder, const std::string& named,
                                   std::string_view what, const PathConfinement& confinement);

}  // namespace ffdkit::meshio
