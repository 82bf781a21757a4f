#pragma once

#include <filesystem>
#include <string_view>

namespace ffdkit::scenes {

/// Writes `content` to `path` atomically: into a temporary file in the same folder, flushed
/// to disk, then renamed over `path`. A failure at any step removes the temporary file and
/// leaves an existing `path` untouched, so readers never see a truncated file.
/// @throws std::runtime_error naming the path and the reason.
void writeFileAtomically(const std::filesystem::path& path, std::string_view content);

}  // namespace ffdkit::scenes
