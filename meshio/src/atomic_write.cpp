#include "ffdkit/meshio/atomic_write.h"

#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <stdexcept>
#include <string>

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

namespace ffdkit::meshio {

namespace {

std::filesystem::path folderOf(const std::filesystem::path& path) {
  return path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
}

std::string temporaryPrefix(const std::filesystem::path& path) {
  // Built by appending: GCC 12 warns falsely (-Wrestrict, bug 105329) on a "." + string chain.
  std::string prefix = ".";
  prefix.append(path.filename().string()).append(".tmp-");
  return prefix;
}

}  // namespace

std::filesystem::path temporaryPathBeside(const std::filesystem::path& path) {
  static std::atomic<unsigned> counter{0};
  std::string name = temporaryPrefix(path);
  name.append(std::to_string(::getpid())).append("-").append(std::to_string(counter.fetch_add(1)));
  return folderOf(path) / name;
}

int removeStaleTemporaries(const std::filesystem::path& path) {
  const std::string prefix = temporaryPrefix(path);
  std::error_code ec;
  std::filesystem::directory_iterator it(folderOf(path), ec), end;
  int removed = 0;
  for (; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    // ".<name>.tmp-<pid>-<n>": the writer's pid decides whether the file is still being written.
    const char* first = name.data() + prefix.size();
    const char* last = name.data() + name.size();
    long pid = 0;
    const auto [next, error] = std::from_chars(first, last, pid);
    if (error != std::errc() || next == last || *next != '-' || pid <= 0) continue;
    if (pid == ::getpid()) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // alive, or not ours to judge
    // A file, or a folder a killed writer was filling (an OpenFOAM case): removed whole (a
    // symbolic link itself, not what it leads to).
    std::error_code ignored;
    if (std::filesystem::remove_all(it->path(), ignored) > 0) ++removed;
  }
  return removed;
}

namespace {

/// The temporary file's bytes as they arrive; a failed step throws naming `path` and the step.
class TemporaryFileSink final : public ByteSink {
 public:
  /// `offset`: where the bytes go in the file (they follow one another from there).
  TemporaryFileSink(const std::filesystem::path& path, int fd, bool durable, off_t offset = 0)
      : path_(path), fd_(fd), durable_(durable), offset_(offset) {}

  void write(std::string_view bytes) override {
    const off_t first = offset_;
    while (!bytes.empty()) {
      const ssize_t n = ::pwrite(fd_, bytes.data(), bytes.size(), offset_);
      if (n < 0) {
        if (errno == EINTR) continue;
        fail("write");
      }
      bytes.remove_prefix(std::size_t(n));
      offset_ += n;
    }
    // Start the disk's work on these pages now; fsync at the end then waits only for the tail.
    // (A hint: where the file system does not support it, fsync does all the work as before.)
    if (durable_ && offset_ > first) ::sync_file_range(fd_, first, offset_ - first, SYNC_FILE_RANGE_WRITE);
  }

  [[noreturn]] void fail(const std::string& step) const {
    throw std::runtime_error(path_.string() + ": cannot write (" + step + ": " + std::strerror(errno) + ")");
  }
  off_t offset() const { return offset_; }  ///< where the next bytes go

 private:
  const std::filesystem::path& path_;
  int fd_;
  bool durable_;
  off_t offset_;
};

}  // namespace

StagedFile::StagedFile(const std::filesystem::path& path, std::string_view content, bool durable)
    : StagedFile(path, [content](ByteSink& sink) { sink.write(content); }, durable) {}

StagedFile::StagedFile(const std::filesystem::path& path, const ByteProducer& produce, bool durable)
    : path_(path), temporary_(temporaryPathBeside(path)) {
  removeStaleTemporaries(path);
  const int fd = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    const std::string reason = std::strerror(errno);
    throw std::runtime_error(path.string() + ": cannot write (create temporary file: " + reason + ")");
  }
  TemporaryFileSink sink(path, fd, durable);
  try {
    produce(sink);
    if (durable && ::fsync(fd) != 0) sink.fail("flush");
  } catch (...) {
    ::close(fd);
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
    throw;
  }
  if (::close(fd) != 0) {
    const std::string reason = std::strerror(errno);
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
    throw std::runtime_error(path.string() + ": cannot write (close: " + reason + ")");
  }
}

StagedFile::~StagedFile() {
  if (temporary_.empty()) return;
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
}

StagedFile::StagedFile(StagedFile&& other) noexcept
    : path_(std::move(other.path_)), temporary_(std::move(other.temporary_)) {
  other.temporary_.clear();
}

void StagedFile::commit() {
  if (temporary_.empty()) throw std::logic_error(path_.string() + ": staged file committed twice");
  if (::rename(temporary_.c_str(), path_.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    throw std::runtime_error(path_.string() + ": cannot write (rename: " + reason + ")");
  }
  temporary_.clear();
}

void writeStagedPart(const std::filesystem::path& temporary, const std::filesystem::path& destination,
                     std::uint64_t offset, std::string_view bytes, bool durable) {
  writeStagedPart(temporary, destination, offset, [bytes](ByteSink& sink) { sink.write(bytes); }, durable);
}

std::uint64_t writeStagedPart(const std::filesystem::path& temporary, const std::filesystem::path& destination,
                              std::uint64_t offset, const ByteProducer& produce, bool durable) {
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) {
    const std::string reason = std::strerror(errno);
    throw std::runtime_error(destination.string() + ": cannot write (open the temporary file " + temporary.string() + ": " + reason + ")");
  }
  TemporaryFileSink sink(destination, fd, durable, off_t(offset));
  try {
    produce(sink);
    if (durable && ::fsync(fd) != 0) sink.fail("flush");
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0) {
    const std::string reason = std::strerror(errno);
    throw std::runtime_error(destination.string() + ": cannot write (close: " + reason + ")");
  }
  return std::uint64_t(sink.offset()) - offset;
}

void writeFileAtomically(const std::filesystem::path& path, std::string_view content, bool durable) {
  StagedFile(path, content, durable).commit();
}

}  // namespace ffdkit::meshio
