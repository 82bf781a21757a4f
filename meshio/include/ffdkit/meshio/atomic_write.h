#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string_view>

namespace ffdkit::meshio {

/// Receives a file's bytes in order, piece by piece (a StagedFile's temporary file, or a
/// string in memory), so that a writer can hand over what it has formatted while it formats
/// the rest.
class ByteSink {
 public:
  /// @throws std::runtime_error when the bytes cannot be stored (e.g. the disk is full).
  virtual void write(std::string_view bytes) = 0;

 protected:
  ~ByteSink() = default;
};

/// Writes a whole file into the sink it is given.
using ByteProducer = std::function<void(ByteSink&)>;

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
  /// Streams the file: each piece `produce` writes goes to the temporary file at once and, when
  /// `durable`, its write-back to disk starts then (sync_file_range), so the disk works while
  /// later pieces are still being made and the final fsync waits only for the tail.
  /// @throws std::runtime_error naming the path and the failed step, or what `produce` throws
  ///         (the temporary file is removed either way).
  StagedFile(const std::filesystem::path& path, const ByteProducer& produce, bool durable = true);
  ~StagedFile();
  /// Takes over `other`'s temporary file.
  StagedFile(StagedFile&& other) noexcept;
  StagedFile& operator=(StagedFile&&) = delete;
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;

  /// Renames the temporary file over the destination. @throws std::runtime_error.
  void commit();
  /// The file commit() writes.
  const std::filesystem::path& destination() const { return path_; }
  /// Where the bytes wait until commit() (other processes may fill parts of it: writeStagedPart).
  const std::filesystem::path& temporary() const { return temporary_; }

 private:
  std::filesystem::path path_;
  std::filesystem::path temporary_;  ///< empty once committed or moved from
};

/// Writes `bytes` at `offset` into the temporary file of a StagedFile that another process (or
/// this one) holds: each process of a batch writing its own part of one file, which the holder
/// commits once every part is written. Flushed to disk before it returns when `durable`.
/// @throws std::runtime_error naming `destination` (the file the temporary becomes) and the step.
void writeStagedPart(const std::filesystem::path& temporary, const std::filesystem::path& destination,
                     std::uint64_t offset, std::string_view bytes, bool durable = true);
/// The same, streaming: what `produce` writes goes to the file at once. Returns the bytes written.
std::uint64_t writeStagedPart(const std::filesystem::path& temporary, const std::filesystem::path& destination,
                              std::uint64_t offset, const ByteProducer& produce, bool durable = true);

/// Writes `content` to `path` atomically: StagedFile(path, content, durable).commit(). A failure
/// at any step removes the temporary file and leaves an existing `path` untouched.
/// @throws std::runtime_error naming the path and the reason.
void writeFileAtomically(const std::filesystem::path& path, std::string_view content, bool durable = true);

/// A fresh hidden file name in `path`'s folder for writing `path` atomically:
/// `.<name>.tmp-<pid>-<n>` (the whole file name kept, so the owner of a temporary is clear).
std::filesystem::path temporaryPathBeside(const std::filesystem::path& path);

/// Removes temporaries of `path` (see temporaryPathBeside: files, or folders with what they hold)
/// whose writing process no longer exists. Returns how many were removed.
int removeStaleTemporaries(const std::filesystem::path& path);

}  // namespace ffdkit::meshio
