// SU2's native mesh format (SU2 documentation, "Mesh File"): `NDIME= d`, then `NELEM= n` with
// one element per line (its VTK type, its point indices from 0, an optional index), `NPOIN= n`
// with one point per line (d coordinates, an optional index), and `NMARK= m` boundary markers
// (`MARKER_TAG= name`, `MARKER_ELEMS= k`, k boundary elements). `%` starts a comment line. Only
// the coordinates are rewritten; lines this reader does not know are kept as they are.
#include <algorithm>
#include <climits>

#include "volume_formats.h"

namespace ffdkit::meshio::detail {

namespace {

// VTK cell types SU2 uses, their point counts and shapes.
bool su2Type(int type, int& nodes, int& dimension, CellShape& shape) {
  switch (type) {
    case 1: nodes = 1, dimension = 0, shape = CellShape::Triangle; return true;  // vertex
    case 3: nodes = 2, dimension = 1, shape = CellShape::Triangle; return true;  // line
    case 5: nodes = 3, dimension = 2, shape = CellShape::Triangle; return true;
    case 9: nodes = 4, dimension = 2, shape = CellShape::Quadrilateral; return true;
    case 10: nodes = 4, dimension = 3, shape = CellShape::Tetrahedron; return true;
    case 12: nodes = 8, dimension = 3, shape = CellShape::Hexahedron; return true;
    case 13: nodes = 6, dimension = 3, shape = CellShape::Prism; return true;
    case 14: nodes = 5, dimension = 3, shape = CellShape::Pyramid; return true;
    default: return false;
  }
}

// "KEY= value": the key when `line` (without leading blanks) is one, else empty.
std::string_view keyOf(std::string_view line) {
  const std::size_t eq = line.find('=');
  if (eq == std::string_view::npos || eq == 0) return {};
  std::string_view key = line.substr(0, eq);
  while (!key.empty() && (key.back() == ' ' || key.back() == '\t')) key.remove_suffix(1);
  for (char c : key)
    if (!((c >= 'A' && c <= 'Z') || c == '_' || (c >= '0' && c <= '9'))) return {};
  return key;
}

struct Su2Reader {
  Su2Reader(LineScanner& scanner, ReadBudget& b, TextVolumeFile& f) : s(scanner), budget(b), file(f) {}
  LineScanner& s;
  ReadBudget& budget;
  TextVolumeFile& file;
  int dimension = 0;
  std::int64_t pointCount = -1;
  std::int64_t largestIndex = -1;  // of the elements and markers, checked once NPOIN is known
  int largestIndexLine = 0;
  std::int64_t elements = 0, markers = 0, markerElements = 0;
  std::vector<std::string> markerNames;

  // The integer after "KEY=" on the line just started.
  long long keyValue(std::string_view key, long long lo, long long hi) {
    s.skipBlanks(false);
    (void)s.token(false, '=');  // the key
    s.skipBlanks(false);
    if (s.atEnd() || s.text()[s.pos()] != '=') s.fail(std::string(key) + ": expected '='");
    s.moveTo(s.pos() + 1);
    return s.integer(key, lo, hi, false);
  }

  // Skips blank and comment lines; false at the end.
  bool nextContent() {
    for (;;) {
      s.skipBlanks();
      if (s.atEnd()) return false;
      if (s.text()[s.pos()] != '%') return true;
      (void)s.takeLine();
    }
  }

  void noteIndex(long long index) {
    if (index > largestIndex) {
      largestIndex = index;
      largestIndexLine = s.line();
    }
  }

  void readElements(std::int64_t n, bool cells, const std::string& what) {
    // At least "1 0" and a line end each; the file's last line may have none (hence the + 1).
    if (std::uint64_t(n) > (s.bytesLeft() + 1) / 4)
      s.fail(what + ": " + std::to_string(n) + " elements need at least 4 bytes each, the file has " +
             std::to_string(s.bytesLeft()) + " left (truncated, or the count is wrong)");
    if (cells) budget.chargeBytes(std::uint64_t(n), 1 + 8 + 8 + 32, what + ": cells");
    std::int32_t corners[8];
    for (std::int64_t e = 0; e < n; ++e) {
      if (!nextContent()) s.fail(what + ": the file ends after " + std::to_string(e) + " of " + std::to_string(n) + " elements");
      const std::string element = what + ": element " + std::to_string(e);
      const int type = int(s.integer(element + " type", 0, INT_MAX));
      int nodes = 0, dim = 0;
      CellShape shape{};
      if (!su2Type(type, nodes, dim, shape))
        s.fail(element + ": VTK type " + std::to_string(type) + " is not one SU2 uses (1, 3, 5, 9, 10, 12, 13, 14)");
      for (int k = 0; k < nodes; ++k) {
        const long long index = s.integer(element + " point", 0, INT32_MAX - 1, false);
        noteIndex(index);
        if (k < 8) corners[k] = std::int32_t(index);
      }
      (void)s.takeLine();  // an optional index follows
      if (cells && dim == dimension) {
        // SU2 stores a prism in VTK's order, its triangles turned the other way from Gmsh's.
        if (shape == CellShape::Prism) {
          std::swap(corners[1], corners[2]);
          std::swap(corners[4], corners[5]);
        }
        file.cells.add(shape, corners, e);
      } else if (cells && dim != dimension) {
        s.failAt(s.line() - 1, element + ": a " + std::to_string(dim) + "D element in a " + std::to_string(dimension) +
                                   "D mesh's NELEM");
      }
    }
  }

  void readPoints(std::int64_t n) {
    // A digit and a blank or line end per coordinate; the file's last line may have no line end.
    if (std::uint64_t(n) > (s.bytesLeft() + 1) / std::uint64_t(2 * dimension))
      s.fail("NPOIN: " + std::to_string(n) + " points need at least " + std::to_string(2 * dimension) +
             " bytes each, the file has " + std::to_string(s.bytesLeft()) + " left (truncated, or the count is wrong)");
    budget.chargePoints(std::uint64_t(n), "NPOIN: " + std::to_string(n) + " points");
    budget.chargeBytes(std::uint64_t(n), 12 * std::uint64_t(dimension), "NPOIN: coordinate positions");
    file.points = Eigen::MatrixX3d::Zero(Eigen::Index(n), 3);
    file.spans.perPoint = dimension;
    file.spans.starts.reserve(std::size_t(n * dimension));
    file.spans.lengths.reserve(std::size_t(n * dimension));
    for (std::int64_t i = 0; i < n; ++i) {
      if (!nextContent()) s.fail("NPOIN: the file ends after " + std::to_string(i) + " of " + std::to_string(n) + " points");
      for (int c = 0; c < dimension; ++c) {
        std::size_t start = 0, length = 0;
        file.points(Eigen::Index(i), c) = s.number("point " + std::to_string(i), false, &start, &length);
        file.spans.add(start, length);
      }
      (void)s.takeLine();  // an optional index follows
    }
    pointCount = n;
  }

  void read() {
    while (nextContent()) {
      const int line = s.line();
      const std::string_view rest = s.text().substr(s.pos(), std::min<std::size_t>(s.bytesLeft(), 64));
      const std::string_view key = keyOf(rest.substr(0, rest.find('\n')));
      if (key == "NDIME") {
        if (dimension != 0) s.fail("a second NDIME");
        dimension = int(keyValue(key, 2, 3));
        (void)s.takeLine();
      } else if (key == "NZONE") {
        if (keyValue(key, 1, INT_MAX) != 1) s.failAt(line, "NZONE: a mesh of several zones is not supported (one zone only)");
        (void)s.takeLine();
      } else if (key == "NELEM") {
        if (dimension == 0) s.fail("NELEM before NDIME");
        if (!file.cells.shapes.empty()) s.fail("a second NELEM");
        const std::int64_t n = keyValue(key, 0, LLONG_MAX);
        (void)s.takeLine();
        readElements(n, true, "NELEM");
        elements = n;
      } else if (key == "NPOIN") {
        if (dimension == 0) s.fail("NPOIN before NDIME");
        if (pointCount >= 0) s.fail("a second NPOIN");
        const std::int64_t n = keyValue(key, 0, INT32_MAX);
        (void)s.takeLine();  // an optional count of domain points follows
        readPoints(n);
      } else if (key == "NMARK") {
        if (dimension == 0) s.fail("NMARK before NDIME");
        const std::int64_t n = keyValue(key, 0, std::int64_t(s.bytesLeft() / 16));
        (void)s.takeLine();
        for (std::int64_t m = 0; m < n; ++m) {
          if (!nextContent()) s.fail("NMARK: the file ends after " + std::to_string(m) + " of " + std::to_string(n) + " markers");
          std::string_view tagLine = s.takeLine();
          if (keyOf(tagLine) != "MARKER_TAG") s.failAt(s.line() - 1, "marker " + std::to_string(m) + ": expected MARKER_TAG=");
          tagLine.remove_prefix(tagLine.find('=') + 1);
          const std::size_t first = tagLine.find_first_not_of(" \t");
          const std::string name(first == std::string_view::npos ? std::string_view() : tagLine.substr(first));
          if (!nextContent()) s.fail("marker " + name + ": expected MARKER_ELEMS=");
          if (keyOf(s.text().substr(s.pos(), std::min<std::size_t>(s.bytesLeft(), 64))) != "MARKER_ELEMS")
            s.fail("marker " + name + ": expected MARKER_ELEMS=");
          const std::int64_t k = keyValue("MARKER_ELEMS", 0, LLONG_MAX);
          (void)s.takeLine();
          readElements(k, false, "marker " + name);
          markerElements += k;
          markerNames.push_back(name);
        }
        markers = n;
      } else {
        (void)s.takeLine();  // a line this reader does not interpret: kept as it is
      }
    }
    if (dimension == 0) s.fail("no NDIME (not an SU2 mesh)");
    if (pointCount < 0) s.fail("no NPOIN section");
    if (largestIndex >= pointCount)
      s.failAt(largestIndexLine, "point index " + std::to_string(largestIndex) + " is not one of the " +
                                     std::to_string(pointCount) + " points (NPOIN)");
  }
};

}  // namespace

TextVolumeFile readSu2(std::string bytes, const std::string& source, ReadBudget& budget) {
  TextVolumeFile file;
  file.bytes = std::move(bytes);
  LineScanner s(file.bytes, source);
  Su2Reader reader(s, budget, file);
  reader.read();
  file.hasCells = true;
  std::string names;
  for (const auto& name : reader.markerNames) names += (names.empty() ? "" : ", ") + name;
  file.summary = std::to_string(reader.dimension) + "D, " + std::to_string(file.points.rows()) + " points, " +
                 std::to_string(reader.elements) + " elements, " + std::to_string(reader.markers) + " markers (" +
                 std::to_string(reader.markerElements) + " boundary elements): " + names;
  return file;
}

}  // namespace ffdkit::meshio::detail
