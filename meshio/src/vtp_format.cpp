// VTK XML poly data (.vtp), read by ffdkit (VTK's reader trusts the file: fuzz_mesh_vtp made it
// write past its own arrays). Every Piece's points and its vertex, line, polygon and strip
// cells, in order: the pieces are joined, each piece's point ids shifted by the points before
// it. Polygons are fan-triangulated and strips split as VTK's triangle filter does; lines are
// split into segments; vertex cells are checked and dropped. Every element a Piece declares is
// read once: a second <Points>, <Polys> (or Verts, Lines, Strips) in one Piece, a Points with
// more than one DataArray, a polygon of fewer than 3 points or a line of fewer than 2 is an
// error, never ignored. Writing stays with VTK (vtk_formats.cpp).
#include <algorithm>
#include <charconv>
#include <climits>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "formats.h"
#include "parse_support.h"
#include "vtk_xml_arrays.h"
#include "vtk_xml_tree.h"

namespace ffdkit::meshio::detail {
namespace {

struct PieceReader {
  const VtkXmlDocument& document;
  const VtkXmlDataLayout& layout;
  const std::string& source;
  ArrayBudget& budget;

  [[noreturn]] void fail(const XmlElement& element, const std::string& message) const {
    throw MeshIoError(document.where(source, element) + message);
  }

  // A Piece's NumberOf... attribute (0 when absent).
  std::size_t count(const XmlElement& piece, const char* name) const {
    const auto text = piece.attribute(name);
    if (!text) return 0;
    unsigned long long value = 0;
    const auto r = std::from_chars(text->data(), text->data() + text->size(), value);
    if (r.ec != std::errc() || r.ptr != text->data() + text->size())
      fail(piece, std::string("Piece: ") + name + "=\"" + std::string(*text) + "\" is not a count");
    // A point or a cell takes at least one byte even compressed 1100:1 (vtk_xml_arrays.cpp).
    if (value > 1100 * std::max<std::uint64_t>(document.bytes.size(), 1 << 16))
      fail(piece, std::string("Piece: ") + name + " announces " + std::to_string(value) + ", more than a file of " +
                      std::to_string(document.bytes.size()) + " bytes can hold");
    return std::size_t(value);
  }

  // The one DataArray named `name` (any name when empty) of `parent`; a second is an error.
  const XmlElement& dataArray(const XmlElement& parent, std::string_view name, const char* what) const {
    const XmlElement* found = nullptr;
    for (const XmlElement& c : parent.children)
      if (c.name == "DataArray" && (name.empty() || c.attribute("Name") == name)) {
        if (found != nullptr)
          fail(c, std::string(what) + ": a second DataArray" + (name.empty() ? std::string() : " \"" + std::string(name) + "\"") +
                      " (one is read)");
        found = &c;
      }
    if (found == nullptr)
      fail(parent, std::string(what) + ": no DataArray" + (name.empty() ? std::string() : " \"" + std::string(name) + "\""));
    return *found;
  }

  // The piece's one child element `name`, or null; a second is an error.
  const XmlElement* onlyChild(const XmlElement& piece, const char* name) const {
    const XmlElement* found = nullptr;
    for (const XmlElement& c : piece.children)
      if (c.name == name) {
        if (found != nullptr) fail(c, std::string("Piece: a second <") + name + "> (one is read)");
        found = &c;
      }
    return found;
  }

  // Charges `count` values of `bytesEach` held while a piece is read, naming the element.
  void charge(const XmlElement& element, std::uint64_t count, std::uint64_t bytesEach, const std::string& what) const {
    try {
      budget.held.chargeBytes(count, bytesEach, what);
    } catch (const ReadLimitError& e) {
      fail(element, e.what());
    }
  }

  // Calls `cell(ids, size)` for each of the `cells` cells of the piece's `elementName` (Verts,
  // Lines, Polys, Strips), after checking the offsets run in order and every id is one of the
  // piece's `points`.
  template <class Cell>
  void forEachCell(const XmlElement& piece, const char* elementName, const char* kind, std::size_t cells, std::size_t points,
                   Cell&& cell) const {
    const XmlElement* element = onlyChild(piece, elementName);
    if (cells == 0) return;
    if (element == nullptr) fail(piece, std::string("Piece: ") + std::to_string(cells) + " " + kind + " cells but no <" + elementName + ">");
    const XmlElement& offsetsArray = dataArray(*element, "offsets", elementName);
    const XmlElement& connectivityArray = dataArray(*element, "connectivity", elementName);
    charge(offsetsArray, cells, sizeof(std::int64_t), std::string(elementName) + " offsets");
    const std::vector<std::int64_t> offsets = readIntegerValues(document, layout, offsetsArray, cells, source, budget);
    std::int64_t previous = 0;
    for (std::size_t c = 0; c < cells; ++c) {
      if (offsets[c] < previous)
        fail(offsetsArray, Where{kind, (long long)c}.text() + ": offset " + std::to_string(offsets[c]) + " is before the previous " +
                               std::to_string(previous));
      previous = offsets[c];
    }
    charge(connectivityArray, std::uint64_t(previous), sizeof(std::int64_t), std::string(elementName) + " connectivity");
    const std::vector<std::int64_t> ids = readIntegerValues(document, layout, connectivityArray, std::size_t(previous), source, budget);
    std::int64_t begin = 0;
    for (std::size_t c = 0; c < cells; ++c) {
      for (std::int64_t k = begin; k < offsets[c]; ++k)
        if (ids[std::size_t(k)] < 0 || std::uint64_t(ids[std::size_t(k)]) >= points)
          fail(connectivityArray, Where{kind, (long long)c}.text() + ": point id " + std::to_string(ids[std::size_t(k)]) +
                                      " is outside 0.." + std::to_string((long long)points - 1));
      cell(ids.data() + begin, std::size_t(offsets[c] - begin), c, connectivityArray);
      begin = offsets[c];
    }
    budget.held.releaseBytes((std::uint64_t(cells) + std::uint64_t(previous)) * sizeof(std::int64_t));
  }
};

bool hasNormals(const XmlElement& piece) {
  const XmlElement* pointData = piece.child("PointData");
  if (pointData == nullptr) return false;
  const auto name = pointData->attribute("Normals");
  if (!name || name->empty()) return false;
  for (const XmlElement& array : pointData->children)
    if (array.name == "DataArray" && array.attribute("Name") == *name && array.attribute("NumberOfComponents") == std::string_view("3"))
      return true;
  return false;
}

}  // namespace

MeshData readVtp(std::string_view bytes, const std::string& source, ReadBudget& readBudget) {
  const VtkXmlDocument document = parseVtkXml(bytes, source);
  const XmlElement& root = document.root;
  const auto type = root.attribute("type").value_or("");
  if (type != "PolyData")
    throw MeshIoError(document.where(source, root) + "a VTK " + (type.empty() ? std::string("XML") : std::string(type)) +
                      " file, not PolyData");
  const VtkXmlDataLayout layout = VtkXmlDataLayout::of(document, source);
  const XmlElement* polyData = root.child("PolyData");
  if (polyData == nullptr) throw MeshIoError(document.where(source, root) + "VTKFile has no <PolyData>");
  ArrayBudget budget(readBudget);
  const PieceReader reader{document, layout, source, budget};

  Eigen::MatrixX3d points;  // grown piece by piece once a piece's values are read (never from a count alone)
  TriangleSink triangles(0, &readBudget, "polygons and strips (their triangles)");
  SegmentSink segments(0, &readBudget, "lines (their segments)");
  bool normals = false;
  for (const XmlElement& piece : polyData->children) {
    if (piece.name != "Piece") continue;
    const std::size_t pointCount = reader.count(piece, "NumberOfPoints");
    const std::size_t verts = reader.count(piece, "NumberOfVerts"), lines = reader.count(piece, "NumberOfLines");
    const std::size_t strips = reader.count(piece, "NumberOfStrips"), polys = reader.count(piece, "NumberOfPolys");
    const int base = int(points.rows());
    const XmlElement* pointsElement = reader.onlyChild(piece, "Points");
    if (pointCount > 0) {
      if (pointsElement == nullptr) reader.fail(piece, "Piece: " + std::to_string(pointCount) + " points but no <Points>");
      const XmlElement& array = reader.dataArray(*pointsElement, "", "Points");
      if (array.attribute("NumberOfComponents") != std::string_view("3"))
        reader.fail(array, "DataArray \"" + std::string(array.attribute("Name").value_or("")) + "\": points need NumberOfComponents=\"3\"");
      if (std::uint64_t(points.rows()) + pointCount > std::uint64_t(INT_MAX))
        reader.fail(piece, "Piece: more points than ffdkit indexes (" + std::to_string(INT_MAX) + ")");
      try {
        readBudget.chargePoints(pointCount, "Piece: NumberOfPoints=" + std::to_string(pointCount));
      } catch (const ReadLimitError& e) {
        reader.fail(piece, e.what());
      }
      reader.charge(array, pointCount, 3 * sizeof(double), "Points values");
      const std::vector<double> xyz = readRealValues(document, layout, array, 3 * pointCount, source, budget);
      points.conservativeResize(points.rows() + Eigen::Index(pointCount), Eigen::NoChange);
      adviseHugePages(points);
      points.bottomRows(Eigen::Index(pointCount)) = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
          xyz.data(), Eigen::Index(pointCount), 3);
      readBudget.releaseBytes(std::uint64_t(pointCount) * 3 * sizeof(double));
      normals = normals || hasNormals(piece);
    }
    // A cell too short to give what it is read as (a segment, a triangle) is an error, not a drop.
    const auto fewest = [&](std::size_t n, std::size_t least, const char* kind, std::size_t c, const XmlElement& array) {
      if (n < least)
        reader.fail(array, Where{kind, (long long)c}.text() + ": needs at least " + std::to_string(least) + " points, it has " +
                               std::to_string(n));
    };
    reader.forEachCell(piece, "Verts", "vertex cell", verts, pointCount,
                       [&](const std::int64_t*, std::size_t n, std::size_t c, const XmlElement& a) { fewest(n, 1, "vertex cell", c, a); });
    reader.forEachCell(piece, "Lines", "line", lines, pointCount,
                       [&](const std::int64_t* line, std::size_t n, std::size_t c, const XmlElement& a) {
      fewest(n, 2, "line", c, a);
      for (std::size_t k = 0; k + 1 < n; ++k) segments.add(base + int(line[k]), base + int(line[k + 1]));
    });
    reader.forEachCell(piece, "Polys", "polygon", polys, pointCount,
                       [&](const std::int64_t* polygon, std::size_t n, std::size_t c, const XmlElement& a) {
      fewest(n, 3, "polygon", c, a);
      for (std::size_t k = 1; k + 1 < n; ++k) triangles.add(base + int(polygon[0]), base + int(polygon[k]), base + int(polygon[k + 1]));
    });
    reader.forEachCell(piece, "Strips", "strip", strips, pointCount,
                       [&](const std::int64_t* strip, std::size_t n, std::size_t c, const XmlElement& a) {
      fewest(n, 3, "strip", c, a);
      for (std::size_t k = 0; k + 2 < n; ++k) {
        if (k % 2 == 0) triangles.add(base + int(strip[k]), base + int(strip[k + 1]), base + int(strip[k + 2]));
        else triangles.add(base + int(strip[k + 1]), base + int(strip[k]), base + int(strip[k + 2]));
      }
    });
  }
  MeshData mesh;
  mesh.points = std::move(points);
  if (mesh.points.rows() == 0) throw MeshIoError(source + ": the file has no points");
  mesh.triangles = triangles.take();
  mesh.segments = segments.take();
  mesh.hasNormals = normals;
  return mesh;
}

}  // namespace ffdkit::meshio::detail
