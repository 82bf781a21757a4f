#include "ffdkit/meshio/path_confinement.h"

#include <algorithm>

namespace ffdkit::meshio {

namespace fs = std::filesystem;

bool isInsideFolder(const fs::path& named, const fs::path& folder) {
  std::error_code ec;
  const fs::path root = fs::weakly_canonical(folder.empty() ? fs::path(".") : folder, ec);
  if (ec) return false;
  const fs::path full = fs::weakly_canonical(named.is_absolute() ? named : (folder.empty() ? fs::path(".") : folder) / named, ec);
  if (ec) return false;
  // Compare whole components: /a/bc is not inside /a/b. A trailing empty component of `root`
  // ("/a/b/" gives "/a/b/" + "") matches anything.
  auto rootEnd = root.end();
  if (!root.empty() && std::prev(rootEnd)->empty()) --rootEnd;
  const auto [end, ignored] = std::mismatch(root.begin(), rootEnd, full.begin(), full.end());
  return end == rootEnd;
}

fs::path confinedPath(const fs::path& folder, const std::string& named, std::string_view what,
                      const PathConfinement& confinement) {
  const fs::path path(named);
  if (!confinement.allowOutside && !isInsideFolder(path, folder))
    throw PathOutsideFolderError(std::string(what) + " '" + named +
                                 "' is outside the folder of the file that names it (a shared file must not read "
                                 "other files; allow it with --allow-outside or the app's preference)");
  return path.is_absolute() ? path : (folder.empty() ? fs::path(".") : folder) / path;
}

}  // namespace ffdkit::meshio
