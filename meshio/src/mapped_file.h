#pragma once
// A file's bytes mapped read-only: the page cache's own pages, so that reading a large polyMesh
// file (a 600 MB `faces`) neither allocates nor clears a buffer of its size. The label lists of
// `faces`, `owner` and `neighbour` are read where they lie in the mapping (LabelList::inPlace,
// which keeps the mapping for as long as the lists live); a parser that copies a file's items out
// (the points) gives back the pages it has copied as it goes (releaseParsedBytes, while a
// GiveBackParsedPages of the file lives), so that the file never stays resident whole beside the
// arrays made from it. Private to meshio.
//
// A file that another process truncates while it is mapped ends the reading process (SIGBUS) where
// read() would have seen a short file, and one that another process rewrites in place changes
// under the lists read from it: the files mapped are a case's own polyMesh files, which nothing
// else writes while a deformation reads and checks them.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "ffdkit/meshio/mesh_data.h"

namespace ffdkit::meshio::detail {

/// A regular file mapped read-only (MAP_PRIVATE) for as long as the object lives.
class MappedFile {
 public:
  /// Maps `path`. @throws MeshIoError naming it when it cannot be opened, is not a regular file,
  /// or cannot be mapped.
  explicit MappedFile(const std::filesystem::path& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw MeshIoError(path.string() + ": cannot open (" + std::strerror(errno) + ")");
    struct stat info {};
    if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
      ::close(fd);
      throw MeshIoError(path.string() + ": not a regular file");
    }
    size_ = std::size_t(info.st_size);
    if (size_ > 0) {
      void* data = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
      if (data == MAP_FAILED) {
        const std::string why = std::strerror(errno);
        ::close(fd);
        throw MeshIoError(path.string() + ": cannot map the file to read it (" + why + ")");
      }
      data_ = static_cast<const char*>(data);
      // Read front to back: the kernel reads ahead and maps the pages in larger runs.
      (void)::madvise(data, size_, MADV_SEQUENTIAL);
    }
    ::close(fd);
  }
  ~MappedFile() {
    if (data_ != nullptr) ::munmap(const_cast<char*>(data_), size_);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  /// The file's bytes.
  std::string_view view() const { return {data_ == nullptr ? "" : data_, size_}; }

  /// Whether [begin, end) lies in the mapping.
  bool holds(const char* begin, const char* end) const {
    return data_ != nullptr && begin >= data_ && end <= data_ + size_;
  }

  /// Drops the whole pages inside [begin, end), which lie in the mapping: the process no longer
  /// holds them (touched again, they are mapped again from the page cache).
  static void dropPages(const char* begin, const char* end) {
    const std::uintptr_t page = std::uintptr_t(::sysconf(_SC_PAGESIZE));
    const std::uintptr_t first = (reinterpret_cast<std::uintptr_t>(begin) + page - 1) & ~(page - 1);
    const std::uintptr_t last = reinterpret_cast<std::uintptr_t>(end) & ~(page - 1);
    if (last > first) (void)::madvise(reinterpret_cast<void*>(first), last - first, MADV_DONTNEED);
  }

 private:
  const char* data_ = nullptr;
  std::size_t size_ = 0;
};

/// While it lives, releaseParsedBytes on this thread gives back the pages of `file` that a parser
/// is done with. Scopes nest (one per parse, on the parsing thread's stack); the file outlives it.
class GiveBackParsedPages {
 public:
  explicit GiveBackParsedPages(const MappedFile* file) : file_(file), previous_(active()) { active() = this; }
  ~GiveBackParsedPages() { active() = previous_; }
  GiveBackParsedPages(const GiveBackParsedPages&) = delete;
  GiveBackParsedPages& operator=(const GiveBackParsedPages&) = delete;

  /// Drops the pages of [begin, end) when they lie in a file of a scope of this thread.
  static void release(const char* begin, const char* end) {
    for (const GiveBackParsedPages* s = active(); s != nullptr; s = s->previous_)
      if (s->file_ != nullptr && s->file_->holds(begin, end)) {
        MappedFile::dropPages(begin, end);
        return;
      }
  }

 private:
  static const GiveBackParsedPages*& active() {
    static thread_local const GiveBackParsedPages* scope = nullptr;
    return scope;
  }
  const MappedFile* file_;
  const GiveBackParsedPages* previous_;
};

/// A parser is done with the bytes [begin, end) of its input: given back when the input is a
/// MappedFile of a live GiveBackParsedPages (its pages leave the process), nothing otherwise (a
/// buffer in memory, a file read in place, stays as it is).
inline void releaseParsedBytes(const char* begin, const char* end) { GiveBackParsedPages::release(begin, end); }

}  // namespace ffdkit::meshio::detail
