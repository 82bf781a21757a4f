// An OpenFOAM case or polyMesh folder: finding its files, reading them into an OpenFoamMesh, and
// writing the folder back with new points, all or nothing.
#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <optional>
#include <stdexcept>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "ffdkit/meshio/atomic_write.h"
#include "ffdkit/meshio/openfoam.h"
#include "ffdkit/meshio/read_failures.h"
#include "formats.h"
#include "mapped_file.h"
#include "parse_support.h"
#include "openfoam_files.h"

namespace ffdkit::meshio {

namespace fs = std::filesystem;

namespace {

bool hasFile(const fs::path& folder, const std::string& name) {
  std::error_code ec;
  return fs::is_regular_file(folder / name, ec) || fs::is_regular_file(folder / (name + ".gz"), ec);
}

bool isPolyMeshFolder(const fs::path& folder) { return hasFile(folder, "points") && hasFile(folder, "faces"); }

// The file `name` of the polyMesh folder, or `name.gz`; empty when neither is there.
fs::path meshFile(const fs::path& polyMesh, const std::string& name) {
  std::error_code ec;
  if (fs::exists(fs::symlink_status(polyMesh / name, ec))) return polyMesh / name;
  if (fs::exists(fs::symlink_status(polyMesh / (name + ".gz"), ec))) return polyMesh / (name + ".gz");
  return {};
}

std::string readWholeFile(const fs::path& path) {
  std::string bytes;
  detail::readRegularFile(path, [&bytes](std::size_t size) {
    bytes.resize(size);
    return bytes.data();
  });
  return bytes;
}

void refuseOutside(const fs::path& path, const fs::path& root, const OpenFoamReadOptions& options) {
  if (!options.confinement.allowOutside && !isInsideFolder(path, root))
    throw MeshIoError(path.string() + ": a symbolic link that leads outside the folder " + root.string() +
                      " (refused: a case must not make ffdkit read other files; allow it with --allow-outside)");
}

// The bytes of one polyMesh file (inflated when it is .gz), after the confinement rule: a file
// that is a symbolic link out of `root` is refused. For the points file, which the writer keeps.
std::string meshFileBytes(const fs::path& path, const fs::path& root, const OpenFoamReadOptions& options,
                          ReadBudget& budget) {
  refuseOutside(path, root, options);
  std::string bytes = readWholeFile(path);
  if (path.extension() == ".gz") return gunzipBytes(bytes, path.string(), budget);
  return bytes;
}

// A file's bytes (points, faces, owner, neighbour): the file mapped (no buffer of its size,
// mapped_file.h), or a .gz file inflated into memory. The label lists of faces, owner and
// neighbour are read where they lie in these bytes, which live as long as the lists (shared).
class ParsedFileBytes {
 public:
  ParsedFileBytes(const fs::path& path, const fs::path& root, const OpenFoamReadOptions& options, ReadBudget& budget) {
    refuseOutside(path, root, options);
    if (path.extension() == ".gz") {
      inflated_ = gunzipBytes(readWholeFile(path), path.string(), budget);
      return;
    }
    mapped_.emplace(path);
  }
  std::string_view view() const { return mapped_ ? mapped_->view() : std::string_view(inflated_); }
  /// The mapping, null for an inflated file.
  const detail::MappedFile* mapping() const { return mapped_ ? &*mapped_ : nullptr; }

 private:
  std::optional<detail::MappedFile> mapped_;
  std::string inflated_;
};

// What the writer keeps of a points file read from `bytes`: all of it (ASCII, whose unchanged
// values keep their text), or a binary file without its items (the coordinates it replaces).
void keepPointsFileBytes(std::string_view bytes, FoamPointsFile& file) {
  if (!file.layout.binary) {
    file.bytes = std::string(bytes);
    return;
  }
  file.bytes.reserve(file.listBegin + (bytes.size() - file.listEnd));
  file.bytes.append(bytes.substr(0, file.listBegin)).append(bytes.substr(file.listEnd));
  file.omittedBytes = file.listEnd - file.listBegin;
  file.listEnd = file.listBegin;
}

fs::path requiredFile(const fs::path& polyMesh, const std::string& name) {
  fs::path path = meshFile(polyMesh, name);
  if (path.empty())
    throw MeshIoError(polyMesh.string() + ": no '" + name + "' file (nor " + name +
                      ".gz): an OpenFOAM polyMesh needs points, faces, owner, neighbour and boundary");
  return path;
}

void refuseDecomposedCase(const fs::path& root) {
  std::error_code ec;
  for (fs::directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind("processor", 0) == 0 && it->is_directory(ec))
      throw MeshIoError(root.string() + ": a decomposed case (" + name +
                        "/): its meshes are read one by one (ffdkit-cli deform takes the case, docs/volume-meshes.md); "
                        "give a processor folder, or reconstruct the case with reconstructParMesh");
  }
}

// The largest label of `list` (-1 for none), on every core.
std::int32_t largestLabel(const LabelList& list) {
  const char* bytes = list.bytes();
  const std::int64_t n = std::int64_t(list.size());
  std::int32_t largest = -1;
#pragma omp parallel for schedule(static) reduction(max : largest) if (n > (1 << 20))
  for (std::int64_t i = 0; i < n; ++i) {
    std::int32_t label;
    std::memcpy(&label, bytes + i * std::int64_t(sizeof label), sizeof label);
    largest = std::max(largest, label);
  }
  return largest;
}

// The first internal face with the same cell as owner and neighbour, -1 for none; on every core.
std::int64_t firstFaceInOneCell(const PolyMeshCells& cells) {
  const char* owner = cells.owner.bytes();
  const char* neighbour = cells.neighbour.bytes();
  const std::int64_t n = std::int64_t(std::min(cells.owner.size(), cells.neighbour.size()));
  constexpr std::int64_t kRun = std::int64_t(1) << 16;
  std::int64_t first = n;
#pragma omp parallel for schedule(static) reduction(min : first) if (n > (1 << 20))
  for (std::int64_t run = 0; run < (n + kRun - 1) / kRun; ++run) {
    const std::int64_t begin = run * kRun, end = std::min(n, begin + kRun);
    bool same = false;  // one branch-free pass over the run; the loop below finds the face
    for (std::int64_t f = begin; f < end; ++f) {
      std::int32_t a, b;
      std::memcpy(&a, owner + f * 4, 4);
      std::memcpy(&b, neighbour + f * 4, 4);
      same |= a == b;
    }
    for (std::int64_t f = begin; same && f < end; ++f)
      if (std::memcmp(owner + f * 4, neighbour + f * 4, 4) == 0) {
        first = std::min(first, f);
        break;
      }
  }
  return first < n ? first : -1;
}

// Each cell's faces in `list` (owner or neighbour), counted up to 4 (a saturating count).
std::vector<std::uint8_t> facesUpToFour(const LabelList& list, std::int64_t cellCount) {
  std::vector<std::uint8_t> count(std::size_t(cellCount), 0);
  const char* bytes = list.bytes();
  for (std::size_t i = 0; i < list.size(); ++i) {
    std::int32_t c;
    std::memcpy(&c, bytes + i * sizeof c, sizeof c);
    count[std::size_t(c)] += count[std::size_t(c)] < 4 ? 1 : 0;
  }
  return count;
}

// Every cell owns or neighbours at least 4 faces (a tetrahedron has 4). The owner and the
// neighbour faces are counted on a core each; where a cell has fewer than 4 in all, neither count
// stopped at 4, so their sum is its number of faces.
void checkCellFaces(const PolyMeshCells& cells, const fs::path& owner, ReadBudget& budget) {
  budget.chargeBytes(std::uint64_t(cells.cellCount), sizeof(std::int32_t), "cells: face counts");
  std::vector<std::uint8_t> owned, neighboured;
#pragma omp parallel sections
  {
#pragma omp section
    owned = facesUpToFour(cells.owner, cells.cellCount);
#pragma omp section
    neighboured = facesUpToFour(cells.neighbour, cells.cellCount);
  }
  for (std::size_t c = 0; c < owned.size(); ++c)
    if (owned[c] + neighboured[c] < 4)
      throw MeshIoError(owner.string() + ": cell " + std::to_string(c) + " has " + std::to_string(owned[c] + neighboured[c]) +
                        " face(s) in owner and neighbour; a cell needs at least 4");
  budget.releaseBytes(std::uint64_t(cells.cellCount) * sizeof(std::int32_t));
}

// The body of readOpenFoamMesh, charging `budget`.
OpenFoamMesh readMeshFolder(const fs::path& folder, const OpenFoamReadOptions& options, ReadBudget& budget) {
  OpenFoamMesh mesh;
  mesh.root = folder;
  mesh.polyMesh = openFoamPolyMeshFolder(folder);
  refuseDecomposedCase(folder);

  const fs::path pointsPath = requiredFile(mesh.polyMesh, "points");
  {
    const ParsedFileBytes pointsBytes(pointsPath, folder, options, budget);
    // The points are copied out (the deformation moves them): their pages go back as they are.
    const detail::GiveBackParsedPages giveBack(pointsBytes.mapping());
    mesh.points = readFoamPoints(pointsBytes.view(), pointsPath.string(), budget, &mesh.pointsFile);
    keepPointsFileBytes(pointsBytes.view(), mesh.pointsFile);
  }
  mesh.pointsFile.gzip = pointsPath.extension() == ".gz";
  mesh.pointsFile.fileName = pointsPath.filename().string();
  if (!options.readCells) return mesh;

  // Read in place: the bytes stay (mapped) for as long as the lists read from them.
  auto fileBytes = [&](const fs::path& path) { return std::make_shared<const ParsedFileBytes>(path, folder, options, budget); };
  const fs::path facesPath = requiredFile(mesh.polyMesh, "faces");
  {
    const auto bytes = fileBytes(facesPath);
    detail::readFoamFacesInPlace(bytes->view(), facesPath.string(), mesh.points.rows(), budget, mesh.cells, bytes);
  }
  const std::int64_t faceCount = std::int64_t(mesh.cells.faceStarts.size()) - 1;

  const fs::path ownerPath = requiredFile(mesh.polyMesh, "owner");
  {
    const auto bytes = fileBytes(ownerPath);
    mesh.cells.owner = detail::readFoamLabelsInPlace(bytes->view(), ownerPath.string(), INT32_MAX - 1, budget, bytes);
  }
  if (std::int64_t(mesh.cells.owner.size()) != faceCount)
    throw MeshIoError(ownerPath.string() + ": " + std::to_string(mesh.cells.owner.size()) + " owner cells for the " +
                      std::to_string(faceCount) + " faces of " + facesPath.filename().string() + " (one per face)");

  const fs::path neighbourPath = requiredFile(mesh.polyMesh, "neighbour");
  {
    const auto bytes = fileBytes(neighbourPath);
    mesh.cells.neighbour = detail::readFoamLabelsInPlace(bytes->view(), neighbourPath.string(), INT32_MAX - 1, budget, bytes);
  }
  if (std::int64_t(mesh.cells.neighbour.size()) > faceCount)
    throw MeshIoError(neighbourPath.string() + ": " + std::to_string(mesh.cells.neighbour.size()) +
                      " neighbour cells for " + std::to_string(faceCount) + " faces (at most one per face)");

  const std::int32_t lastCell = std::max(largestLabel(mesh.cells.owner), largestLabel(mesh.cells.neighbour));
  mesh.cells.cellCount = std::int64_t(lastCell) + 1;
  if (mesh.cells.cellCount == 0) throw MeshIoError(ownerPath.string() + ": the mesh has no cells");
  if (const std::int64_t f = firstFaceInOneCell(mesh.cells); f >= 0)
    throw MeshIoError(neighbourPath.string() + ": face " + std::to_string(f) + " has cell " +
                      std::to_string(mesh.cells.owner[std::size_t(f)]) + " on both sides");
  checkCellFaces(mesh.cells, ownerPath, budget);
  // What the cell check allocates (meshio/cell_quality.h): each cell's faces (4 bytes per cell
  // and per cell-face pair), then its centre and a flag.
  budget.chargeBytes(std::uint64_t(mesh.cells.cellCount) + std::uint64_t(faceCount) + mesh.cells.neighbour.size(), 4,
                     "cells: the faces of each cell for the cell check");
  budget.chargeBytes(std::uint64_t(mesh.cells.cellCount), 25, "cells: centres of the cell check");

  const fs::path boundaryPath = requiredFile(mesh.polyMesh, "boundary");
  mesh.patches = readFoamBoundary(meshFileBytes(boundaryPath, folder, options, budget), boundaryPath.string(),
                                  std::int64_t(mesh.cells.neighbour.size()), faceCount);
  return mesh;
}

}  // namespace

namespace detail {

void writeNewFile(const fs::path& path, std::string_view bytes, bool durable) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) throw MeshIoError(path.string() + ": cannot create (" + std::strerror(errno) + ")");
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string why = std::strerror(errno);
      ::close(fd);
      throw MeshIoError(path.string() + ": cannot write (" + why + ")");
    }
    bytes.remove_prefix(std::size_t(n));
  }
  if ((durable && ::fsync(fd) != 0) || ::close(fd) != 0)
    throw MeshIoError(path.string() + ": cannot write (" + std::strerror(errno) + ")");
}

namespace {

// A file descriptor closed when it goes.
struct OpenFile {
  explicit OpenFile(int descriptor) : fd(descriptor) {}
  ~OpenFile() {
    if (fd >= 0) ::close(fd);
  }
  OpenFile(const OpenFile&) = delete;
  OpenFile& operator=(const OpenFile&) = delete;
  int fd;
};

// Files from this size on are copied by direct I/O when they are flushed anyway (copyFileDirectly);
// smaller ones by the kernel's copy.
constexpr std::uintmax_t kDirectCopyFrom = std::uintmax_t(4) << 20;
// The source is mapped this much at a time (a multiple of the page size).
constexpr std::size_t kDirectCopyWindow = std::size_t(64) << 20;
// Direct I/O writes whole blocks of this many bytes (a multiple of every device's logical block);
// the file's last bytes, after its last whole block, are written through the page cache.
constexpr std::size_t kDirectBlock = 4096;

[[noreturn]] void failCopy(const fs::path& to, const std::string& step) {
  throw MeshIoError(to.string() + ": cannot write (" + step + ": " + std::strerror(errno) + ")");
}

// How writeFully ended.
enum class FullWrite { Written, DirectRefused, Failed };

// Writes all `length` bytes of `data` at `offset` of `fd`, again after EINTR and short writes.
// DirectRefused: the file system refused direct I/O (`direct`) at the file's first byte (EINVAL
// there; nothing written). Failed: errno says why (EIO for a write of nothing).
FullWrite writeFully(int fd, const char* data, std::size_t length, std::uint64_t offset, bool direct) {
  for (std::size_t done = 0; done < length;) {
    const ssize_t n = ::pwrite(fd, data + done, length - done, off_t(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno == EINVAL && direct && offset + done == 0) return FullWrite::DirectRefused;
    if (n <= 0) {
      if (n == 0) errno = EIO;
      return FullWrite::Failed;
    }
    done += std::size_t(n);
  }
  return FullWrite::Written;
}

// A new file written from a buffer that the caller fills piece by piece: through the page cache,
// or by direct I/O (O_DIRECT: whole blocks go to the disk from the buffer, aligned to a block,
// as it fills; the last partial block through the page cache; buffered writes where the file
// system takes no direct I/O).
class NewFileWriter {
 public:
  static constexpr std::size_t kCapacity = std::size_t(8) << 20;

  NewFileWriter(const fs::path& path, bool direct)
      : path_(path), file_(::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | (direct ? O_DIRECT : 0), 0644)),
        direct_(direct) {
    if (file_.fd < 0 && direct && errno == EINVAL) {
      file_.fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
      direct_ = false;
    }
    if (file_.fd < 0) throw MeshIoError(path.string() + ": cannot create (" + std::strerror(errno) + ")");
    void* buffer = nullptr;
    if (::posix_memalign(&buffer, kDirectBlock, kCapacity) != 0) throw std::bad_alloc();
    buffer_.reset(static_cast<char*>(buffer));
  }

  /// Room for `bytes` (at most kCapacity - kDirectBlock) at the end of the buffer, valid until
  /// the next call; advance() then takes what was written there.
  char* space(std::size_t bytes) {
    if (fill_ + bytes > kCapacity) writeBlocks();
    return buffer_.get() + fill_;
  }
  void advance(std::size_t bytes) { fill_ += bytes; }
  void append(std::string_view bytes) {
    while (!bytes.empty()) {
      const std::size_t n = std::min(bytes.size(), kCapacity - kDirectBlock);
      std::memcpy(space(n), bytes.data(), n);
      advance(n);
      bytes.remove_prefix(n);
    }
  }
  /// Writes what is left and closes the file, flushed to disk first when `durable`.
  void finish(bool durable) {
    writeBlocks();
    if (fill_ > 0) {
      if (direct_ && ::fcntl(file_.fd, F_SETFL, ::fcntl(file_.fd, F_GETFL) & ~O_DIRECT) != 0) fail();
      direct_ = false;
      writeBlocks();
    }
    if (durable && ::fsync(file_.fd) != 0) fail();
    const int fd = file_.fd;
    file_.fd = -1;
    if (::close(fd) != 0) fail();
  }

 private:
  [[noreturn]] void fail() const { throw MeshIoError(path_.string() + ": cannot write (" + std::strerror(errno) + ")"); }
  // Writes the buffer's whole blocks (direct I/O; all of it otherwise) and keeps the rest at its start.
  void writeBlocks() {
    const std::size_t length = direct_ ? fill_ - fill_ % kDirectBlock : fill_;
    FullWrite result = writeFully(file_.fd, buffer_.get(), length, offset_, direct_);
    if (result == FullWrite::DirectRefused) {  // no direct I/O here after all
      if (::fcntl(file_.fd, F_SETFL, ::fcntl(file_.fd, F_GETFL) & ~O_DIRECT) != 0) fail();
      direct_ = false;
      result = writeFully(file_.fd, buffer_.get(), length, offset_, false);
    }
    if (result != FullWrite::Written) fail();
    std::memmove(buffer_.get(), buffer_.get() + length, fill_ - length);
    offset_ += length;
    fill_ -= length;
  }

  struct Free {
    void operator()(char* p) const { std::free(p); }
  };
  const fs::path& path_;
  OpenFile file_;
  bool direct_;
  std::unique_ptr<char, Free> buffer_;
  std::size_t fill_ = 0;    // bytes in the buffer
  std::uint64_t offset_ = 0;  // where the buffer's first byte goes in the file
};

}  // namespace

void writeFoamPointsFile(const fs::path& path, const FoamPointsFile& original, const Eigen::MatrixX3d& points,
                         bool durable, bool direct) {
  if (!original.layout.binary || original.gzip) {
    std::string bytes = foamPointsBytes(original, points);
    if (original.gzip) bytes = gzipBytes(bytes, original.fileName);
    writeNewFile(path, bytes, durable);
    return;
  }
  checkBinaryFoamPoints(original, points);
  NewFileWriter file(path, direct);
  const std::string_view kept = original.bytes;
  file.append(kept.substr(0, original.listBegin));
  // 64 Ki points (1.5 MiB of doubles) at a time, formatted into the writer's buffer.
  constexpr Eigen::Index kRun = Eigen::Index(1) << 16;
  const std::size_t runBytes = std::size_t(kRun) * 3 * std::size_t(original.layout.scalarBytes);
  for (Eigen::Index first = 0; first < points.rows(); first += kRun) {
    const Eigen::Index last = std::min(points.rows(), first + kRun);
    char* run = file.space(runBytes);
    file.advance(std::size_t(storeFoamPoints(original.layout, points, first, last, run) - run));
  }
  file.append(kept.substr(original.listEnd));
  file.finish(durable);
}

void syncPath(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

void startWriteback(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return;
  ::sync_file_range(fd, 0, 0, SYNC_FILE_RANGE_WRITE);
  ::close(fd);
}

bool copyFileDirectly(const fs::path& from, const fs::path& to) {
  const OpenFile in(::open(from.c_str(), O_RDONLY | O_CLOEXEC));
  struct stat source {};
  if (in.fd < 0 || ::fstat(in.fd, &source) != 0 || !S_ISREG(source.st_mode)) return false;  // copy_file says why
  OpenFile out(::open(to.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_DIRECT, S_IWUSR));
  if (out.fd < 0) {
    if (errno == EINVAL) return false;  // no direct I/O on this file system
    failCopy(to, "create");
  }
  // Taken back where the file system refuses direct I/O at the first write.
  auto giveUp = [&] {
    ::close(out.fd);
    out.fd = -1;
    std::error_code ignored;
    fs::remove(to, ignored);
    return false;
  };
  if (::fchmod(out.fd, source.st_mode & 07777) != 0) failCopy(to, "set its permissions");
  const std::size_t size = std::size_t(source.st_size);
  const std::size_t whole = size - size % kDirectBlock;
  for (std::size_t at = 0; at < whole; at += kDirectCopyWindow) {
    const std::size_t length = std::min(kDirectCopyWindow, whole - at);
    void* window = ::mmap(nullptr, length, PROT_READ, MAP_SHARED | MAP_POPULATE, in.fd, off_t(at));
    if (window == MAP_FAILED) failCopy(to, "map " + from.string());
    const FullWrite result = writeFully(out.fd, static_cast<const char*>(window), length, at, true);
    const int error = errno;
    ::munmap(window, length);
    if (result == FullWrite::DirectRefused) return giveUp();
    if (result == FullWrite::Failed) {
      errno = error;
      failCopy(to, "write");
    }
  }
  if (size > whole) {
    char tail[kDirectBlock];
    const std::size_t count = size - whole;
    if (::pread(in.fd, tail, count, off_t(whole)) != ssize_t(count)) failCopy(to, "read " + from.string());
    if (::fcntl(out.fd, F_SETFL, ::fcntl(out.fd, F_GETFL) & ~O_DIRECT) != 0) failCopy(to, "write");
    if (::pwrite(out.fd, tail, count, off_t(whole)) != ssize_t(count)) failCopy(to, "write");
  }
  if (::close(out.fd) != 0) {
    out.fd = -1;
    failCopy(to, "close");
  }
  out.fd = -1;
  return true;
}

namespace {

// A file copyFolder copies: from, to, and its size (the larger are copied first).
struct FileCopy {
  fs::path from, to;
  std::uintmax_t bytes = 0;
};

// copyFolder's walk: makes the folders (`folders` receives them) and lists the files to copy.
void copyInto(const fs::path& from, const fs::path& to, const fs::path& root,
              const std::function<bool(const fs::path&)>& skip, std::vector<FileCopy>& files, std::vector<fs::path>& folders) {
  for (const fs::directory_entry& entry : fs::directory_iterator(from)) {
    const fs::path target = to / entry.path().filename();
    if (skip(entry.path())) continue;
    const fs::file_status link = entry.symlink_status();
    if (fs::is_symlink(link)) {
      if (!isInsideFolder(entry.path(), root))
        throw MeshIoError(entry.path().string() + ": a symbolic link that leads outside the folder " + root.string() +
                          " (refused: the written case would hold another file's bytes)");
      if (fs::is_directory(entry.path()))
        throw MeshIoError(entry.path().string() + ": a symbolic link to a folder (not copied; make it a folder)");
    }
    if (fs::is_directory(entry.status())) {
      fs::create_directory(target);
      copyInto(entry.path(), target, root, skip, files, folders);
    } else if (fs::is_regular_file(entry.status())) {
      files.push_back({entry.path(), target, fs::file_size(entry.path())});
    } else {
      throw MeshIoError(entry.path().string() + ": neither a file nor a folder (not copied)");
    }
  }
  folders.push_back(to);
}

}  // namespace

void copyFolder(const fs::path& from, const fs::path& to, const fs::path& root,
                const std::function<bool(const fs::path&)>& skip, bool durable, const std::function<void()>& alongside,
                bool everyCore) {
  std::vector<FileCopy> files;
  std::vector<fs::path> folders;
  copyInto(from, to, root, skip, files, folders);
  // The copies (the kernel's: copy_file) and `alongside` shared by the cores, the largest first:
  // job 0 is `alongside`, job j > 0 copies files[j - 1].
  std::stable_sort(files.begin(), files.end(), [](const FileCopy& a, const FileCopy& b) { return a.bytes > b.bytes; });
  const std::int64_t jobs = std::int64_t(files.size()) + 1;
  std::exception_ptr failure;
#pragma omp parallel for schedule(dynamic, 1) if (everyCore && jobs > 2)
  for (std::int64_t j = 0; j < jobs; ++j) {
    try {
      if (j == 0) {
        if (alongside) alongside();
        continue;
      }
      const FileCopy& file = files[std::size_t(j - 1)];
      // A large file that is flushed anyway goes to the disk from the source's cached pages.
      if (durable && file.bytes >= kDirectCopyFrom && copyFileDirectly(file.from, file.to)) continue;
      fs::copy_file(file.from, file.to);
      // The disk starts on this file while the next ones are copied; the flush at the end waits.
      if (durable) startWriteback(file.to);
    } catch (...) {
#pragma omp critical(ffdkit_copy_folder_failure)
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
  if (!durable) return;
  for (const FileCopy& file : files) syncPath(file.to);
  for (const fs::path& folder : folders) syncPath(folder);
}

void checkFolderOutput(const fs::path& rootGiven, const fs::path& output) {
  std::error_code ec;
  const fs::path root = fs::weakly_canonical(rootGiven, ec);
  const fs::path target = fs::weakly_canonical(fs::absolute(output), ec);
  if (target != root && isInsideFolder(target, root))
    throw MeshIoError(output.string() + ": the output folder is inside the folder it copies (" + rootGiven.string() + ")");
  if (fs::exists(output) && !fs::is_directory(output))
    throw MeshIoError(output.string() + ": exists and is not a folder");
}

void renameFolderIntoPlace(const fs::path& temporary, const fs::path& output, bool durable) {
  std::error_code ec;
  if (!fs::exists(output)) {
    if (::rename(temporary.c_str(), output.c_str()) != 0)
      throw MeshIoError(output.string() + ": cannot rename the finished copy into place (" + std::strerror(errno) + ")");
  } else {
    // Atomic exchange: `output` is the old folder or the whole new one at every moment.
    if (::renameat2(AT_FDCWD, temporary.c_str(), AT_FDCWD, output.c_str(), RENAME_EXCHANGE) != 0)
      throw MeshIoError(output.string() + ": cannot exchange the finished copy with the existing folder (" +
                        std::strerror(errno) + ")");
    fs::remove_all(temporary, ec);  // the old folder
  }
  if (durable) syncPath(output.has_parent_path() ? output.parent_path() : fs::path("."));
}

}  // namespace detail

bool isOpenFoamMeshFolder(const fs::path& folder) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return false;
  return hasFile(folder / "constant" / "polyMesh", "points") || isPolyMeshFolder(folder);
}

fs::path openFoamPolyMeshFolder(const fs::path& folder) {
  const fs::path inCase = folder / "constant" / "polyMesh";
  std::error_code ec;
  if (fs::is_directory(inCase, ec)) return inCase;
  if (isPolyMeshFolder(folder)) return folder;
  throw MeshIoError(folder.string() + ": not an OpenFOAM case (no constant/polyMesh) nor a polyMesh folder (points and faces)");
}

OpenFoamMesh readOpenFoamMesh(const fs::path& folder, const OpenFoamReadOptions& options) {
  ReadBudget own(options.limits);
  ReadBudget& budget = options.budget != nullptr ? *options.budget : own;
  try {
    return convertReadFailures<MeshIoError>(folder.string(), "the polyMesh", budget,
                                            [&] { return readMeshFolder(folder, options, budget); });
  } catch (const std::length_error&) {
    throw MeshIoError(folder.string() + ": out of memory while reading (a size beyond what can be allocated)");
  } catch (const fs::filesystem_error& e) {
    throw MeshIoError(folder.string() + ": " + e.what());
  }
}

StagedOpenFoamMesh::~StagedOpenFoamMesh() {
  if (temporary_.empty()) return;
  std::error_code ignored;
  fs::remove_all(temporary_, ignored);
}

StagedOpenFoamMesh::StagedOpenFoamMesh(StagedOpenFoamMesh&& other) noexcept
    : temporary_(std::move(other.temporary_)), output_(std::move(other.output_)), durable_(other.durable_) {
  other.temporary_.clear();
}

void StagedOpenFoamMesh::commit() {
  if (temporary_.empty()) throw std::logic_error(output_.string() + ": staged case committed twice");
  detail::renameFolderIntoPlace(temporary_, output_, durable_);
  temporary_.clear();
}

StagedOpenFoamMesh stageOpenFoamMesh(const OpenFoamMesh& mesh, const Eigen::MatrixX3d& points, const fs::path& outputGiven,
                                     const OpenFoamWriteOptions& options) {
  const fs::path output = outputGiven.filename().empty() ? outputGiven.parent_path() : outputGiven;
  detail::checkFolderOutput(mesh.root, output);
  // A point count or value the file cannot hold fails before any copy. A binary file is written
  // from the points (writeFoamPointsFile); the bytes of another are made here.
  const bool streamed = mesh.pointsFile.layout.binary && !mesh.pointsFile.gzip;
  std::string bytes;
  if (streamed) {
    detail::checkBinaryFoamPoints(mesh.pointsFile, points);
  } else {
    bytes = foamPointsBytes(mesh.pointsFile, points);
    if (mesh.pointsFile.gzip) bytes = gzipBytes(bytes, mesh.pointsFile.fileName);
  }

  const fs::path parent = output.has_parent_path() ? output.parent_path() : fs::path(".");
  fs::path temporary = temporaryPathBeside(output);
  removeStaleTemporaries(output);  // hidden folders of writers that were killed
  std::error_code ec;
  try {
    fs::create_directories(parent);
    fs::create_directory(temporary);
  } catch (const fs::filesystem_error& e) {
    fs::remove_all(temporary, ec);
    throw MeshIoError(output.string() + ": cannot write the case (" + e.what() + ")");
  }
  // From here the staged folder removes the hidden one if anything throws.
  StagedOpenFoamMesh staged(temporary, output, options.durable);
  try {
    const fs::path pointsPath = mesh.polyMesh / mesh.pointsFile.fileName;
    const fs::path relativePolyMesh = fs::relative(mesh.polyMesh, mesh.root);
    const fs::path newPoints = temporary / relativePolyMesh / mesh.pointsFile.fileName;
    // The new points file written beside the copies of the rest (on another core), its flush
    // started, then everything flushed: the disk writes while the copies are made.
    fs::create_directories(newPoints.parent_path());
    auto writePoints = [&] {
      // Flushed anyway: by direct I/O, from the buffer the points are formatted into.
      if (streamed) detail::writeFoamPointsFile(newPoints, mesh.pointsFile, points, false, options.durable);
      else detail::writeNewFile(newPoints, bytes, false);
      if (options.durable) detail::startWriteback(newPoints);
    };
    detail::copyFolder(mesh.root, temporary, mesh.root, [&](const fs::path& p) { return p == pointsPath; },
                       options.durable, writePoints, options.everyCore);
    if (options.durable) detail::syncPath(newPoints);
  } catch (const fs::filesystem_error& e) {
    throw MeshIoError(output.string() + ": cannot write the case (" + e.what() + ")");
  }
  return staged;
}

void writeOpenFoamMesh(const OpenFoamMesh& mesh, const Eigen::MatrixX3d& points, const fs::path& output,
                       const OpenFoamWriteOptions& options) {
  stageOpenFoamMesh(mesh, points, output, options).commit();
}

}  // namespace ffdkit::meshio
