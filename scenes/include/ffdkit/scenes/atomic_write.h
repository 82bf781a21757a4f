#pragma once

#include <filesystem>
#include <string_view>

namespace ffdkit::scenes {

/// Writes `content` to `path` atomically: into a temporary file in the same folder, flushed
/// to disk, then renamed over `path`. A failure at any step removes the temporary file and
/// leaves an existing `path` untouched, so readers never see a truncated file.
/// @throws std::runtime_error naming the path and the reason.
void writeFileAtomically(const std::filesystem::path& path, std::string_view content);

/// A fresh hidden file name in `path`'s folder for writing `path` atomically:
/// `.<stem>.tmp-<pid>-<n><extension>` (the extension kept, for writers that look at it).
std::filesystem::path temporaryPathBeside(const std::filesystem::path& path);

}  // namespace ffdkit::scenes
