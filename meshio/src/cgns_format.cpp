// CGNS unstructured zones through the CGNS library's mid-level API (CGNS Mid-Level Library,
// "Grid Coordinates" and "Element Connectivity"): coordinates read as double whatever their
// stored type, element sections to ElementCells, and the write as a copy of the file whose
// coordinate arrays are overwritten in place (cg_coord_partial_write over the whole range, in the
// array's own type).
#include "ffdkit/meshio/cgns.h"

#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <new>
#include <string_view>
#include <type_traits>
#include <vector>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cgnslib.h>

#include "ffdkit/meshio/atomic_write.h"
#include "ffdkit/meshio/mesh_data.h"
#include "ffdkit/meshio/read_failures.h"

#if defined(__SANITIZE_ADDRESS__)
#define FFDKIT_CGNS_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FFDKIT_CGNS_ASAN 1
#endif
#endif
#ifndef FFDKIT_CGNS_ASAN
#define FFDKIT_CGNS_ASAN 0
#endif

namespace ffdkit::meshio {

namespace fs = std::filesystem;

namespace {

// A file opened with cg_open, closed on every path.
class CgnsFile {
 public:
  CgnsFile(const fs::path& path, int mode) : path_(path.string()) {
    if (cg_open(path_.c_str(), mode, &fn_) != CG_OK) {
      fn_ = -1;
      fail("cannot open as a CGNS file");
    }
  }
  ~CgnsFile() { close(); }
  CgnsFile(const CgnsFile&) = delete;
  CgnsFile& operator=(const CgnsFile&) = delete;

  int fn() const { return fn_; }
  /// Closes it (the write is complete only then). @throws MeshIoError.
  void closeChecked() {
    const int fn = fn_;
    fn_ = -1;
    if (fn >= 0 && cg_close(fn) != CG_OK) fail("cannot close");
  }
  /// Throws with the library's last error unless `status` is CG_OK.
  void check(int status, const std::string& what) const {
    if (status != CG_OK) fail(what);
  }
  [[noreturn]] void fail(const std::string& what) const {
    const char* why = cg_get_error();
    throw MeshIoError(path_ + ": " + what + (why != nullptr && *why != '\0' ? std::string(" (") + why + ")" : ""));
  }
  [[noreturn]] void refuse(const std::string& what) const { throw MeshIoError(path_ + ": " + what); }

 private:
  void close() {
    if (fn_ >= 0) cg_close(fn_);
    fn_ = -1;
  }
  std::string path_;
  int fn_ = -1;
};

// The name the library gives `value` of an enumeration with `count` values, or the number for a
// value outside it (a malformed file's).
std::string enumName(const char* const* names, int value, int count) {
  return value >= 0 && value < count ? std::string(names[value]) : "number " + std::to_string(value);
}

// The shape and node count of an element type that is a cell of a mesh of `cellDimension`;
// false for a lower-dimensional (boundary) element. @throws through `file` for a type ffdkit
// does not check.
bool cellShapeOf(ElementType_t type, int cellDimension, CellShape& shape) {
  switch (type) {
    case CGNS_ENUMV(TETRA_4): case CGNS_ENUMV(TETRA_10):
      shape = CellShape::Tetrahedron; return cellDimension == 3;
    case CGNS_ENUMV(PYRA_5): case CGNS_ENUMV(PYRA_13): case CGNS_ENUMV(PYRA_14):
      shape = CellShape::Pyramid; return cellDimension == 3;
    case CGNS_ENUMV(PENTA_6): case CGNS_ENUMV(PENTA_15): case CGNS_ENUMV(PENTA_18):
      shape = CellShape::Prism; return cellDimension == 3;
    case CGNS_ENUMV(HEXA_8): case CGNS_ENUMV(HEXA_20): case CGNS_ENUMV(HEXA_27):
      shape = CellShape::Hexahedron; return cellDimension == 3;
    case CGNS_ENUMV(TRI_3): case CGNS_ENUMV(TRI_6):
      shape = CellShape::Triangle; return cellDimension == 2;
    case CGNS_ENUMV(QUAD_4): case CGNS_ENUMV(QUAD_8): case CGNS_ENUMV(QUAD_9):
      shape = CellShape::Quadrilateral; return cellDimension == 2;
    default:
      return false;
  }
}

bool isKnownLowerElement(ElementType_t type) {
  switch (type) {
    case CGNS_ENUMV(NODE): case CGNS_ENUMV(BAR_2): case CGNS_ENUMV(BAR_3):
    case CGNS_ENUMV(TRI_3): case CGNS_ENUMV(TRI_6):
    case CGNS_ENUMV(QUAD_4): case CGNS_ENUMV(QUAD_8): case CGNS_ENUMV(QUAD_9):
      return true;
    default:
      return false;
  }
}

// Adds one element (its `nodes` node numbers, 1-based) of `type` to `mesh`: a cell by its corners,
// or counted as a boundary element. @throws for a node out of range or an unknown type.
void addElement(const CgnsFile& file, const std::string& where, ElementType_t type, const cgsize_t* nodes, int nodeCount,
                std::int64_t id, std::int64_t pointCount, CgnsMesh& mesh) {
  for (int k = 0; k < nodeCount; ++k)
    if (nodes[k] < 1 || nodes[k] > pointCount)
      file.refuse(where + ", element " + std::to_string(id) + ": node " + std::to_string(nodes[k]) +
                  " is outside 1.." + std::to_string(pointCount));
  CellShape shape{};
  if (cellShapeOf(type, mesh.cellDimension, shape)) {
    std::int32_t corners[8];
    for (int k = 0; k < cornerCount(shape); ++k) corners[k] = std::int32_t(nodes[k] - 1);
    mesh.cells.add(shape, corners, id);
  } else if (isKnownLowerElement(type)) {
    ++mesh.boundaryElements;
  } else {
    file.refuse(where + ", element " + std::to_string(id) + ": element type " + enumName(ElementTypeName, int(type), NofValidElementTypes) +
                " is not read by ffdkit (tetrahedra, pyramids, prisms, hexahedra, their faces and edges)");
  }
}

void readSections(const CgnsFile& file, ReadBudget& budget, std::int64_t pointCount, CgnsMesh& mesh) {
  const int fn = file.fn(), B = mesh.base, Z = mesh.zone;
  int sections = 0;
  file.check(cg_nsections(fn, B, Z, &sections), "cannot count the element sections of zone " + mesh.zoneName);
  for (int S = 1; S <= sections; ++S) {
    char name[33] = {};
    ElementType_t type{};
    cgsize_t start = 0, end = 0;
    int boundary = 0, parentFlag = 0;
    file.check(cg_section_read(fn, B, Z, S, name, &type, &start, &end, &boundary, &parentFlag),
               "cannot read element section " + std::to_string(S));
    const std::string where = "zone " + mesh.zoneName + ", section " + std::to_string(S) + " '" + name + "'";
    if (end < start) file.refuse(where + ": element range " + std::to_string(start) + ".." + std::to_string(end));
    const std::int64_t count = std::int64_t(end) - start + 1;
    cgsize_t dataSize = 0;
    file.check(cg_ElementDataSize(fn, B, Z, S, &dataSize), "cannot size " + where);
    if (dataSize < count) file.refuse(where + ": " + std::to_string(dataSize) + " node numbers for " + std::to_string(count) + " elements");
    if (type == CGNS_ENUMV(NGON_n) || type == CGNS_ENUMV(NFACE_n)) {  // faces and cells of polyhedra: not checked
      mesh.polyhedralElements += count;
      continue;
    }
    budget.chargeBytes(std::uint64_t(dataSize), sizeof(cgsize_t), where + ": connectivity");
    std::vector<cgsize_t> nodes(static_cast<std::size_t>(dataSize));
    if (type == CGNS_ENUMV(MIXED)) {
      budget.chargeBytes(std::uint64_t(count) + 1, sizeof(cgsize_t), where + ": offsets");
      std::vector<cgsize_t> offsets(std::size_t(count) + 1);
      file.check(cg_poly_elements_read(fn, B, Z, S, nodes.data(), offsets.data(), nullptr), "cannot read " + where);
      for (std::int64_t e = 0; e < count; ++e) {
        const cgsize_t first = offsets[std::size_t(e)], last = offsets[std::size_t(e) + 1];
        if (first < 0 || last > dataSize || last - first < 1)
          file.refuse(where + ", element " + std::to_string(start + e) + ": offsets " + std::to_string(first) + ".." + std::to_string(last));
        // The type is checked as a number before it becomes an ElementType_t (a value outside the
        // enumeration is not one).
        const cgsize_t rawType = nodes[std::size_t(first)];
        const bool validType = rawType > cgsize_t(CGNS_ENUMV(ElementTypeUserDefined)) && rawType < cgsize_t(NofValidElementTypes);
        const ElementType_t elementType = validType ? ElementType_t(rawType) : CGNS_ENUMV(ElementTypeNull);
        int npe = 0;
        if (!validType || cg_npe(elementType, &npe) != CG_OK || npe <= 0 || npe != last - first - 1)
          file.refuse(where + ", element " + std::to_string(start + e) + ": type " + std::to_string(nodes[std::size_t(first)]) +
                      " with " + std::to_string(last - first - 1) + " nodes is not a fixed element type ffdkit reads");
        addElement(file, where, elementType, nodes.data() + first + 1, npe, start + e, pointCount, mesh);
      }
      budget.releaseBytes((std::uint64_t(count) + 1) * sizeof(cgsize_t));
    } else {
      int npe = 0;
      if (cg_npe(type, &npe) != CG_OK || npe <= 0)
        file.refuse(where + ": element type " + std::to_string(int(type)) + " is not a fixed element type ffdkit reads");
      if (std::int64_t(dataSize) != count * npe)
        file.refuse(where + ": " + std::to_string(dataSize) + " node numbers for " + std::to_string(count) + " elements of " +
                    std::to_string(npe) + " nodes");
      file.check(cg_elements_read(fn, B, Z, S, nodes.data(), nullptr), "cannot read " + where);
      for (std::int64_t e = 0; e < count; ++e)
        addElement(file, where, type, nodes.data() + e * npe, npe, start + e, pointCount, mesh);
    }
    budget.releaseBytes(std::uint64_t(dataSize) * sizeof(cgsize_t));
  }
}

CgnsMesh readZone(const fs::path& path, const CgnsReadOptions& options, ReadBudget& budget);

// Runs `work` in a child process (fork) with at most `maxSeconds` of CPU time and `maxMemoryBytes`
// of new address space (0: no limit; none under AddressSanitizer, whose shadow memory needs more);
// the bytes it
// appends to its string come back here. A MeshIoError it throws is thrown here with its message.
// A crash (the CGNS library's ADF reader overflows a buffer on some malformed files), a run past
// the limit, or any other end of the child is a MeshIoError naming `file`; this process goes on.
std::string runInChild(const std::string& file, const std::string& doing, double maxSeconds, std::uint64_t maxMemoryBytes,
                       const std::function<void(std::string&)>& work) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw MeshIoError(file + ": cannot start the process " + doing + " it (" + std::strerror(errno) + ")");
  std::fflush(nullptr);
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw MeshIoError(file + ": cannot start the process " + doing + " it (" + std::strerror(errno) + ")");
  }
  if (child == 0) {
    ::close(fds[0]);
    if (maxSeconds > 0) {
      const rlim_t seconds = static_cast<rlim_t>(std::ceil(maxSeconds));
      const rlimit cpu{seconds, seconds + 1};
      ::setrlimit(RLIMIT_CPU, &cpu);
    }
#if !FFDKIT_CGNS_ASAN
    // The library allocates what a file's header announces (and exits when calloc fails): the
    // child may map `maxMemoryBytes` beyond what it inherited.
    if (maxMemoryBytes > 0) {
      unsigned long long pages = 0;
      if (std::FILE* statm = std::fopen("/proc/self/statm", "r")) {
        if (std::fscanf(statm, "%llu", &pages) != 1) pages = 0;
        std::fclose(statm);
      }
      const rlim_t bytes = rlim_t(pages) * rlim_t(::sysconf(_SC_PAGESIZE)) + rlim_t(maxMemoryBytes);
      const rlimit memory{bytes, bytes};
      if (pages > 0) ::setrlimit(RLIMIT_AS, &memory);
    }
#endif
    std::string out;
    int code = 0;
    try {
      work(out);
    } catch (const MeshIoError& e) {
      out = e.what();
      code = 3;
    } catch (const std::bad_alloc&) {
      out = file + ": out of memory " + doing + " it";
      code = 3;
    } catch (...) {
      code = 5;
    }
    for (std::size_t done = 0; done < out.size();) {
      const ssize_t n = ::write(fds[1], out.data() + done, out.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) std::_Exit(6);
      done += std::size_t(n);
    }
    std::_Exit(code);  // no destructor or exit handler of this process's copy runs
  }
  ::close(fds[1]);
  std::string text;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    text.append(buffer, std::size_t(n));
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    if (signal == SIGXCPU || signal == SIGKILL)
      throw MeshIoError(file + ": " + doing + " it took more than " + std::to_string(int(std::ceil(maxSeconds))) +
                        " s of CPU time (CgnsReadOptions::maxSeconds)");
    throw MeshIoError(file + ": the CGNS library crashed " + doing + " it (signal " + std::to_string(signal) +
                      "): the file is malformed");
  }
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (code == 0) return text;
  if (code == 3) throw MeshIoError(text);
  if (code == 5) throw MeshIoError(file + ": an unexpected error " + doing + " it");
  // Any other status is not one the child chose (under AddressSanitizer a crash ends the process
  // with ASan's exit code instead of the signal).
  throw MeshIoError(file + ": the CGNS library crashed " + doing + " it (exit status " + std::to_string(code) +
                    "): the file is malformed");
}

// A CgnsMesh as bytes, from the child that read it to this process.
class MeshWire {
 public:
  template <class T>
  static void put(std::string& out, const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    out.append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  template <class T>
  static void putArray(std::string& out, const T* data, std::size_t count) {
    put(out, std::uint64_t(count));
    out.append(reinterpret_cast<const char*>(data), count * sizeof(T));
  }
  static void putString(std::string& out, const std::string& text) { putArray(out, text.data(), text.size()); }

  static void write(std::string& out, const CgnsMesh& mesh) {
    put(out, mesh.base), put(out, mesh.zone), put(out, mesh.cellDimension), put(out, mesh.physicalDimension);
    put(out, mesh.pointCount), put(out, mesh.boundaryElements), put(out, mesh.polyhedralElements);
    putString(out, mesh.zoneName);
    for (int axis = 0; axis < 3; ++axis) {
      putString(out, mesh.coordinateNames[std::size_t(axis)]);
      put(out, mesh.singlePrecision[std::size_t(axis)]);
    }
    putArray(out, mesh.points.data(), std::size_t(mesh.points.size()));
    putArray(out, mesh.cells.shapes.data(), mesh.cells.shapes.size());
    putArray(out, mesh.cells.cornerStarts.data(), mesh.cells.cornerStarts.size());
    putArray(out, mesh.cells.corners.data(), mesh.cells.corners.size());
    putArray(out, mesh.cells.ids.data(), mesh.cells.ids.size());
  }

  MeshWire(std::string_view bytes, const std::string& file) : bytes_(bytes), file_(file) {}

  CgnsMesh read() {
    CgnsMesh mesh;
    get(mesh.base), get(mesh.zone), get(mesh.cellDimension), get(mesh.physicalDimension);
    get(mesh.pointCount), get(mesh.boundaryElements), get(mesh.polyhedralElements);
    getString(mesh.zoneName);
    for (int axis = 0; axis < 3; ++axis) {
      getString(mesh.coordinateNames[std::size_t(axis)]);
      get(mesh.singlePrecision[std::size_t(axis)]);
    }
    std::vector<double> points;
    getVector(points);
    if (points.size() != 3 * std::size_t(mesh.pointCount)) fail();
    mesh.points = Eigen::Map<const Eigen::MatrixX3d>(points.data(), Eigen::Index(mesh.pointCount), 3);
    getVector(mesh.cells.shapes), getVector(mesh.cells.cornerStarts), getVector(mesh.cells.corners), getVector(mesh.cells.ids);
    if (pos_ != bytes_.size()) fail();
    return mesh;
  }

 private:
  [[noreturn]] void fail() const { throw MeshIoError(file_ + ": the reading process returned a truncated zone"); }
  template <class T>
  void get(T& value) {
    if (bytes_.size() - pos_ < sizeof value) fail();
    std::memcpy(&value, bytes_.data() + pos_, sizeof value);
    pos_ += sizeof value;
  }
  template <class T>
  void getVector(std::vector<T>& values) {
    std::uint64_t count = 0;
    get(count);
    if (count > (bytes_.size() - pos_) / sizeof(T)) fail();
    values.resize(std::size_t(count));
    if (count > 0) std::memcpy(values.data(), bytes_.data() + pos_, std::size_t(count) * sizeof(T));  // data() may be null
    pos_ += std::size_t(count) * sizeof(T);
  }
  void getString(std::string& text) {
    std::vector<char> chars;
    getVector(chars);
    text.assign(chars.begin(), chars.end());
  }
  std::string_view bytes_;
  const std::string& file_;
  std::size_t pos_ = 0;
};

CgnsMesh readCgnsMeshHere(const fs::path& path, const CgnsReadOptions& options);

}  // namespace

bool cgnsSupported() { return true; }

CgnsMesh readCgnsMesh(const fs::path& path, const CgnsReadOptions& options) {
  if (!options.isolate) return readCgnsMeshHere(path, options);
  const std::string file = path.string();
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw MeshIoError(file + ": not a regular file");
  const std::string bytes =
      runInChild(file, "reading", options.maxSeconds, options.limits.maxMemoryBytes, [&](std::string& out) { MeshWire::write(out, readCgnsMeshHere(path, options)); });
  CgnsMesh mesh = MeshWire(bytes, file).read();
  mesh.file = path;
  return mesh;
}

namespace {

CgnsMesh readCgnsMeshHere(const fs::path& path, const CgnsReadOptions& options) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw MeshIoError(path.string() + ": not a regular file");
  int fileType = 0;
  if (cg_is_cgns(path.c_str(), &fileType) != CG_OK)
    throw MeshIoError(path.string() + ": not a CGNS file (neither HDF5 nor ADF with a CGNS tree)");
  ReadBudget budget(options.limits);
  return convertReadFailures<MeshIoError>(path.string(), "the CGNS file", budget,
                                          [&] { return readZone(path, options, budget); });
}

CgnsMesh readZone(const fs::path& path, const CgnsReadOptions& options, ReadBudget& budget) {
  CgnsFile file(path, CG_MODE_READ);
  const int fn = file.fn();
  CgnsMesh mesh;
  mesh.file = path;
  mesh.base = options.base;
  mesh.zone = options.zone;
  int bases = 0;
  file.check(cg_nbases(fn, &bases), "cannot count the bases");
  if (mesh.base < 1 || mesh.base > bases)
    file.refuse("base " + std::to_string(mesh.base) + " does not exist (the file has " + std::to_string(bases) + ")");
  char baseName[33] = {};
  file.check(cg_base_read(fn, mesh.base, baseName, &mesh.cellDimension, &mesh.physicalDimension), "cannot read the base");
  if (mesh.cellDimension < 2 || mesh.cellDimension > 3 || mesh.physicalDimension < mesh.cellDimension ||
      mesh.physicalDimension > 3)
    file.refuse("base '" + std::string(baseName) + "': cell dimension " + std::to_string(mesh.cellDimension) +
                ", physical dimension " + std::to_string(mesh.physicalDimension) + " (ffdkit reads 2D and 3D meshes)");
  int zones = 0;
  file.check(cg_nzones(fn, mesh.base, &zones), "cannot count the zones");
  if (mesh.zone < 1 || mesh.zone > zones)
    file.refuse("base '" + std::string(baseName) + "': zone " + std::to_string(mesh.zone) + " does not exist (it has " +
                std::to_string(zones) + ")");
  ZoneType_t zoneType{};
  file.check(cg_zone_type(fn, mesh.base, mesh.zone, &zoneType), "cannot read the zone type");
  char zoneName[33] = {};
  cgsize_t size[9] = {};
  file.check(cg_zone_read(fn, mesh.base, mesh.zone, zoneName, size), "cannot read the zone");
  mesh.zoneName = zoneName;
  if (zoneType != CGNS_ENUMV(Unstructured))
    file.refuse("zone " + mesh.zoneName + " is structured; ffdkit reads unstructured zones");
  const std::int64_t pointCount = size[0];
  if (pointCount < 1) file.refuse("zone " + mesh.zoneName + ": " + std::to_string(pointCount) + " vertices");
  budget.chargePoints(std::uint64_t(pointCount), "zone " + mesh.zoneName + ": " + std::to_string(pointCount) + " vertices");

  int coordinates = 0;
  file.check(cg_ncoords(fn, mesh.base, mesh.zone, &coordinates), "cannot count the coordinates");
  const char* wanted[3] = {"CoordinateX", "CoordinateY", "CoordinateZ"};
  mesh.pointCount = pointCount;
  mesh.points = Eigen::MatrixX3d::Zero(Eigen::Index(pointCount), 3);
  std::vector<double> values(static_cast<std::size_t>(pointCount));
  for (int axis = 0; axis < mesh.physicalDimension; ++axis) {
    bool found = false;
    for (int C = 1; C <= coordinates && !found; ++C) {
      DataType_t type{};
      char name[33] = {};
      file.check(cg_coord_info(fn, mesh.base, mesh.zone, C, &type, name), "cannot read coordinate " + std::to_string(C));
      if (std::strcmp(name, wanted[axis]) != 0) continue;
      if (type != CGNS_ENUMV(RealDouble) && type != CGNS_ENUMV(RealSingle))
        file.refuse("zone " + mesh.zoneName + ": " + name + " is " + enumName(DataTypeName, int(type), NofValidDataTypes) +
                    ", not RealSingle or RealDouble");
      found = true;
      mesh.coordinateNames[std::size_t(axis)] = name;
      mesh.singlePrecision[std::size_t(axis)] = type == CGNS_ENUMV(RealSingle);
      const cgsize_t first = 1, last = cgsize_t(pointCount);
      file.check(cg_coord_read(fn, mesh.base, mesh.zone, name, CGNS_ENUMV(RealDouble), &first, &last, values.data()),
                 "cannot read " + std::string(name));
      for (std::int64_t i = 0; i < pointCount; ++i) {
        if (!std::isfinite(values[std::size_t(i)]))
          file.refuse("zone " + mesh.zoneName + ": " + name + " of vertex " + std::to_string(i + 1) + " is not finite");
        mesh.points(Eigen::Index(i), axis) = values[std::size_t(i)];
      }
    }
    if (!found)
      file.refuse("zone " + mesh.zoneName + ": no " + wanted[axis] +
                  " (ffdkit reads Cartesian coordinates CoordinateX, CoordinateY, CoordinateZ)");
  }
  readSections(file, budget, pointCount, mesh);
  return mesh;
}

}  // namespace

void writeCgnsMesh(const CgnsMesh& mesh, const Eigen::MatrixX3d& points, const fs::path& output,
                   const CgnsWriteOptions& options) {
  if (points.rows() != mesh.pointCount)
    throw MeshIoError(output.string() + ": " + std::to_string(points.rows()) + " points given for a zone of " +
                      std::to_string(mesh.pointCount) + " vertices");
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    for (int axis = 0; axis < mesh.physicalDimension; ++axis) {
      const double value = points(i, axis);
      const bool single = mesh.singlePrecision[std::size_t(axis)];
      if (!std::isfinite(value) || (single && !std::isfinite(float(value))))
        throw MeshIoError(output.string() + ": vertex " + std::to_string(i + 1) + ": " +
                          mesh.coordinateNames[std::size_t(axis)] + " " + std::to_string(value) +
                          (single ? " is not a finite float32 (the file stores RealSingle)" : " is not finite"));
    }
  std::error_code ec;
  if (fs::exists(output, ec) && fs::equivalent(output, mesh.file, ec))
    throw MeshIoError(output.string() + ": is the file read; write the deformed mesh to another file");
  const fs::path temporary = temporaryPathBeside(output);
  try {
    fs::copy_file(mesh.file, temporary);
    const auto overwrite = [&] {
      CgnsFile file(temporary, CG_MODE_MODIFY);
      std::vector<double> doubles(std::size_t(points.rows()));
      std::vector<float> singles;
      const cgsize_t first = 1, last = cgsize_t(points.rows());
      for (int axis = 0; axis < mesh.physicalDimension; ++axis) {
        const std::string& name = mesh.coordinateNames[std::size_t(axis)];
        for (Eigen::Index i = 0; i < points.rows(); ++i) doubles[std::size_t(i)] = points(i, axis);
        const void* data = doubles.data();
        DataType_t type = CGNS_ENUMV(RealDouble);
        if (mesh.singlePrecision[std::size_t(axis)]) {
          singles.assign(doubles.begin(), doubles.end());
          data = singles.data();
          type = CGNS_ENUMV(RealSingle);
        }
        int C = 0;
        file.check(cg_coord_partial_write(file.fn(), mesh.base, mesh.zone, type, name.c_str(), &first, &last, data, &C),
                   "cannot write " + name);
      }
      file.closeChecked();
    };
    if (options.isolate)
      runInChild(temporary.string(), "writing", 120.0, std::uint64_t(points.rows()) * 64 + (std::uint64_t(1) << 30), [&](std::string&) { overwrite(); });
    else
      overwrite();
    if (options.durable) {
      const int fd = ::open(temporary.c_str(), O_RDONLY | O_CLOEXEC);
      if (fd < 0 || ::fsync(fd) != 0) {
        if (fd >= 0) ::close(fd);
        throw MeshIoError(output.string() + ": cannot flush the written file (" + std::strerror(errno) + ")");
      }
      ::close(fd);
    }
    fs::rename(temporary, output);
  } catch (const fs::filesystem_error& e) {
    fs::remove(temporary, ec);
    throw MeshIoError(output.string() + ": cannot write (" + e.what() + ")");
  } catch (...) {
    fs::remove(temporary, ec);
    throw;
  }
}

bool isCgnsPath(const fs::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".cgns";
}

}  // namespace ffdkit::meshio
