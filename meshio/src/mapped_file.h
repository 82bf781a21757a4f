#pragma once
// A file's bytes mapped read-only for one parse: the page cache's own pages, so that reading a
// large polyMesh file (a 600 MB `faces`) neither allocates nor clears a buffer of its size, and
// the parts a parser has copied out are given back as it goes (releaseParsedBytes), so that the
// file never stays resident whole beside the arrays made from it. Private to meshio.
//
// A file that another process truncates while it is mapped ends the reading process (SIGBUS) where
// read() would have seen a short file: the files mapped are a case's own polyMesh files, read
// once, which nothing else writes while a deformation reads them.

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

/// A regular file mapped read-only (MAP_PRIVATE) for as long as the object lives. While it lives it
/// is the mapping releaseParsedBytes knows on this thread (nested mappings stack).
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
    previous_ = active();
    active() = this;
  }
  ~MappedFile() {
    active() = previous_;
    if (data_ != nullptr) ::munmap(const_cast<char*>(data_), size_);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  /// The file's bytes.
  std::string_view view() const { return {data_ == nullptr ? "" : data_, size_}; }

  /// Drops the whole pages inside [begin, end) when they lie in a mapping of this thread: the
  /// process no longer holds them (touched again, they are mapped again from the page cache).
  static void release(const char* begin, const char* end) {
    for (const MappedFile* m = active(); m != nullptr; m = m->previous_) {
      if (m->data_ == nullptr || begin < m->data_ || end > m->data_ + m->size_) continue;
      const std::uintptr_t page = std::uintptr_t(::sysconf(_SC_PAGESIZE));
      const std::uintptr_t first = (reinterpret_cast<std::uintptr_t>(begin) + page - 1) & ~(page - 1);
      const std::uintptr_t last = reinterpret_cast<std::uintptr_t>(end) & ~(page - 1);
      if (last > first) (void)::madvise(reinterpret_cast<void*>(first), last - first, MADV_DONTNEED);
      return;
    }
  }

 private:
  static const MappedFile*& active() {
    static thread_local const MappedFile* mapping = nullptr;
    return mapping;
  }
  const char* data_ = nullptr;
  std::size_t size_ = 0;
  const MappedFile* previous_ = nullptr;
};

/// A parser is done with the bytes [begin, end) of its input: given back when the input is a
/// MappedFile (its pages leave the process), nothing otherwise (a buffer in memory stays as it is).
inline void releaseParsedBytes(const char* begin, const char* end) { MappedFile::release(begin, end); }

}  // namespace ffdkit::meshio::detail
