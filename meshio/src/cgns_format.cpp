// CGNS unstructured zones through the CGNS library's mid-level API (CGNS Mid-Level Library,
// "Grid Coordinates" and "Element Connectivity"): coordinates read as double whatever their
// stored type, element sections to ElementCells, and the write as a copy of the file whose
// coordinate arrays are overwritten in place (cg_coord_partial_write over the whole range, in the
// array's own type).
#include "ffdkit/meshio/cgns.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include <cgnslib.h>

#include "ffdkit/meshio/atomic_write.h"
#include "ffdkit/meshio/mesh_data.h"
#include "ffdkit/meshio/read_failures.h"

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
    file.refuse(where + ", element " + std::to_string(id) + ": element type " + ElementTypeName[type] +
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
        const ElementType_t elementType = ElementType_t(nodes[std::size_t(first)]);
        int npe = 0;
        if (elementType <= CGNS_ENUMV(ElementTypeUserDefined) || elementType >= NofValidElementTypes ||
            cg_npe(elementType, &npe) != CG_OK || npe <= 0 || npe != last - first - 1)
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

}  // namespace

bool cgnsSupported() { return true; }

CgnsMesh readCgnsMesh(const fs::path& path, const CgnsReadOptions& options) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw MeshIoError(path.string() + ": not a regular file");
  int fileType = 0;
  if (cg_is_cgns(path.c_str(), &fileType) != CG_OK)
    throw MeshIoError(path.string() + ": not a CGNS file (neither HDF5 nor ADF with a CGNS tree)");
  ReadBudget budget(options.limits);
  return convertReadFailures<MeshIoError>(path.string(), "the CGNS file", budget,
                                          [&] { return readZone(path, options, budget); });
}

namespace {

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
        file.refuse("zone " + mesh.zoneName + ": " + name + " is " + DataTypeName[type] + ", not RealSingle or RealDouble");
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
    {
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
    }
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
