#pragma once

#include <filesystem>
#include <string_view>

namespace ffdkit::meshio {

/// A file written beside its destination and not yet in place: the constructor writes
/// `content` to a hidden temporary file in `path`'s folder (flushed to disk when `durable`);
/// commit() renames it over `path`. Destroyed uncommitted, it removes the temporary file.
/// Several StagedFiles committed one after another give "all or nothing" for a batch.
/// The constructor also removes temporaries of `path` left by writers that were killed (their
/// process is gone), so no temporary file survives the next write.
class StagedFile {
 public:
  /// @throws std::runtime_error naming the path and the failed step.
  StagedFile(const std::filesystem::path& path, std::string_view content, bool durable = true);
  ~StagedFile();
  StagedFile(StagedFile&& other) noexcept;
  StagedFile& operator=(StagedFile&&) = delete;
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;

  /// Renames the temporary file over the destination. @throws std::runtime_error.
  void commit();
  const std::filesystem::path& destination() const { return path_; }

 private:
  std::filesystem::path path_;
  std::filesystem::path temporary_;  ///< empty once committed or moved from
};

/// Writes `content` to `path` atomically: StagedFile(path, content, durable).commit(). A failure
/// at any step removes the temporary file and leaves an existing `path` untouched.
/// @throws std::runtime_error naming the path and the reason.
void writeFileAtomically(const std::filesystem::path& path, std::string_view content, bool durable = true);

/// A fresh hidden file name in `path`'s folder for writing `path` atomically:
/// `.<name>.tmp-<pid>-<n>` (the whole file name kept, so the owner of a temporary is clear).
std::filesystem::path temporaryPathBeside(const std::filesystem::path& path);

/// Removes temporaries of `path` (see temporaryPathBeside) whose writing process no longer
/// exists. Returns how many were removed.
int removeStaleTemporaries(const std::filesystem::path& path);

}  // namespace ffdkit::meshio
