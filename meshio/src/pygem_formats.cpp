// The node sections of the formats PyGeM's file handlers read (pygem/unvhandler.py,
// elmerhandler.py, khandler.py, mdpahandler.py): I-DEAS universal dataset 2411, Elmer's
// mesh.nodes, LS-DYNA's *NODE cards and Kratos's "Begin Nodes" blocks. Only the coordinates are
// read and rewritten; every other line is kept as it is. A universal file's elements (dataset
// 2412) are read too, for the cell check of its solids.
#include <algorithm>
#include <charconv>
#include <climits>
#include <map>
#include <unordered_map>

#include "parse_support.h"
#include "volume_formats.h"

namespace ffdkit::meshio::detail {

namespace {

std::string_view trimmed(std::string_view line) {
  const std::size_t first = line.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const std::size_t last = line.find_last_not_of(" \t\r");
  return line.substr(first, last - first + 1);
}

bool startsWith(std::string_view text, std::string_view prefix) { return text.substr(0, prefix.size()) == prefix; }

// Points and their spans collected line by line, charged to the budget as they grow.
struct PointCollector {
  PointSink sink;
  TextVolumeFile& file;
  PointCollector(ReadBudget& budget, TextVolumeFile& f, const char* what) : sink(0, &budget, what, 36), file(f) {}
  // The span of the token at `token` (a view into file.bytes) as one coordinate.
  void span(std::string_view token) { file.spans.add(std::size_t(token.data() - file.bytes.data()), token.size()); }
  void finish() { file.points = sink.take(); }
};

[[noreturn]] void failAt(const std::string& source, int line, const std::string& message) {
  throw MeshIoError(source + ":" + std::to_string(line) + ": " + message);
}

double parsed(std::string_view token, bool fortran, const std::string& source, int line, const std::string& what) {
  double value = 0.0;
  if (!parseNumberToken(token, value, fortran))
    failAt(source, line, what + ": expected a finite number, got '" + std::string(token.substr(0, 40)) + "'");
  return value;
}

// Whitespace-separated tokens of a line.
std::vector<std::string_view> tokens(std::string_view line, char separator = '\0') {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  auto isSep = [&](char c) { return c == ' ' || c == '\t' || c == '\r' || (separator != '\0' && c == separator); };
  while (i < line.size()) {
    while (i < line.size() && isSep(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !isSep(line[i])) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

// Lines of a text with their numbers.
struct Lines {
  std::string_view text;
  std::size_t pos = 0;
  int number = 0;
  bool next(std::string_view& line) {
    if (pos >= text.size()) return false;
    const std::size_t newline = text.find('\n', pos);
    const std::size_t end = newline == std::string_view::npos ? text.size() : newline;
    line = text.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = newline == std::string_view::npos ? text.size() : newline + 1;
    ++number;
    return true;
  }
};

// What the cell check takes of a UNV element type (I-DEAS FE descriptor id): its shape and the
// positions of its corners among its nodes. The linear solids list their corners in Gmsh's order;
// a parabolic solid lists corner and mid-edge nodes alternately round each face, then the
// mid-edges between them (Gmsh's UNV reader, GModelIO_UNV.cpp, maps them the same way); the
// pyramids are Salome's (312, 313), which I-DEAS lacks.
struct UnvSolid {
  int descriptor;
  int nodes;
  CellShape shape;
  std::array<int, 8> corners;
};
constexpr UnvSolid kUnvSolids[] = {
    {111, 4, CellShape::Tetrahedron, {0, 1, 2, 3}},
    {118, 10, CellShape::Tetrahedron, {0, 2, 4, 9}},
    {101, 6, CellShape::Prism, {0, 1, 2, 3, 4, 5}},
    {112, 6, CellShape::Prism, {0, 1, 2, 3, 4, 5}},
    {102, 15, CellShape::Prism, {0, 2, 4, 9, 11, 13}},
    {113, 15, CellShape::Prism, {0, 2, 4, 9, 11, 13}},
    {104, 8, CellShape::Hexahedron, {0, 1, 2, 3, 4, 5, 6, 7}},
    {115, 8, CellShape::Hexahedron, {0, 1, 2, 3, 4, 5, 6, 7}},
    {105, 20, CellShape::Hexahedron, {0, 2, 4, 6, 12, 14, 16, 18}},
    {116, 20, CellShape::Hexahedron, {0, 2, 4, 6, 12, 14, 16, 18}},
    {312, 5, CellShape::Pyramid, {0, 1, 2, 3, 4}},
    {313, 13, CellShape::Pyramid, {0, 2, 4, 6, 12}},
};

const UnvSolid* unvSolid(long long descriptor) {
  for (const UnvSolid& solid : kUnvSolids)
    if (solid.descriptor == descriptor) return &solid;
  return nullptr;
}

// Beams carry a second record (orientation node, cross sections) before their nodes.
bool unvBeam(long long descriptor) {
  switch (descriptor) {
    case 11: case 21: case 22: case 23: case 24: case 31: case 32: return true;
    default: return false;
  }
}

// The kind a summary gives an element type.
const char* unvKind(long long descriptor) {
  if (unvSolid(descriptor) != nullptr) return "solid";
  if (unvBeam(descriptor)) return "beam";
  if (descriptor >= 41 && descriptor <= 99) return "shell";
  return "other";
}

constexpr long long kMaxUnvElementNodes = 64;

long long unvInteger(std::string_view token, const std::string& source, int line, const std::string& what) {
  long long value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc() || end != token.data() + token.size())
    failAt(source, line, what + ": expected an integer, got '" + std::string(token.substr(0, 20)) + "'");
  return value;
}

// A dataset 2412 element as read: its label, type, the line of its first record and its nodes'
// labels (in `labels`, from `firstLabel`); resolved to point rows once every 2411 node is known.
struct UnvElement {
  long long label;
  long long descriptor;
  int line;
  std::size_t firstLabel;
};

}  // namespace

TextVolumeFile readUnv(std::string bytes, const std::string& source, ReadBudget& budget) {
  TextVolumeFile file;
  file.bytes = std::move(bytes);
  file.spans.style = {16, 'E', true, true, true};
  PointCollector points(budget, file, "UNV dataset 2411: nodes");
  Lines lines{file.bytes};
  std::string_view line;
  int datasets = 0, nodeSets = 0, elementSets = 0;
  bool styleSet = false;
  std::vector<long long> nodeLabels;  // per point, in file order
  std::vector<int> nodeLines;
  std::vector<UnvElement> elements;
  std::vector<long long> elementNodes;  // the node labels of every element, in order
  while (lines.next(line)) {
    if (trimmed(line) != "-1") {
      if (trimmed(line).empty()) continue;
      failAt(source, lines.number, "expected '-1' before a dataset, got '" + std::string(line.substr(0, 40)) + "'");
    }
    if (!lines.next(line)) break;  // a trailing delimiter
    const std::string_view id = trimmed(line);
    ++datasets;
    if (id == "2411") {
      ++nodeSets;
      for (;;) {
        if (!lines.next(line)) failAt(source, lines.number, "dataset 2411 is not closed by '-1'");
        if (trimmed(line) == "-1") break;
        const auto head = tokens(line);
        if (head.size() != 4)
          failAt(source, lines.number, "dataset 2411: expected a node record (label, two systems, colour), got '" +
                                           std::string(line.substr(0, 60)) + "'");
        const std::string what = "dataset 2411: node " + std::string(head[0].substr(0, 20));
        budget.chargeBytes(1, sizeof(long long) + sizeof(int), "UNV dataset 2411: node labels");
        nodeLabels.push_back(unvInteger(head[0], source, lines.number, "dataset 2411: node label"));
        nodeLines.push_back(lines.number);
        if (!lines.next(line)) failAt(source, lines.number, what + ": no coordinate record");
        const auto xyz = tokens(line);
        if (xyz.size() != 3) failAt(source, lines.number, what + ": expected 3 coordinates, got " + std::to_string(xyz.size()));
        double v[3];
        for (int c = 0; c < 3; ++c) {
          v[c] = parsed(xyz[std::size_t(c)], true, source, lines.number, what);
          if (!styleSet) {
            file.spans.style.exponent = xyz[0].find_first_of("Dd") != std::string_view::npos ? 'D' : 'E';
            styleSet = true;
          }
          // Each coordinate is a 25-character field (format 3D25.16): its text right-aligned in it.
          const std::size_t end = std::size_t(xyz[std::size_t(c)].data() + xyz[std::size_t(c)].size() - line.data());
          const std::size_t previousEnd = c == 0 ? 0 : std::size_t(xyz[std::size_t(c - 1)].data() + xyz[std::size_t(c - 1)].size() - line.data());
          const std::size_t tokenStart = std::size_t(xyz[std::size_t(c)].data() - line.data());
          const std::size_t start = std::min(tokenStart, end >= previousEnd + 25 ? end - 25 : previousEnd);
          points.span(line.substr(start, end - start));
        }
        points.sink.add(v[0], v[1], v[2]);
      }
    } else if (id == "2412") {
      ++elementSets;
      for (;;) {
        if (!lines.next(line)) failAt(source, lines.number, "dataset 2412 is not closed by '-1'");
        if (trimmed(line) == "-1") break;
        // Record 1 (6I10): label, FE descriptor, physical and material property tables, colour, nodes.
        const auto head = tokens(line);
        if (head.size() != 6)
          failAt(source, lines.number, "dataset 2412: expected an element record (label, type, two tables, colour, node "
                                       "count), got '" + std::string(line.substr(0, 60)) + "'");
        UnvElement element{unvInteger(head[0], source, lines.number, "dataset 2412: element label"),
                           unvInteger(head[1], source, lines.number, "dataset 2412: element type"), lines.number,
                           elementNodes.size()};
        const std::string what = "dataset 2412: element " + std::string(head[0].substr(0, 20));
        const long long count = unvInteger(head[5], source, lines.number, what + ": node count");
        if (count < 1 || count > kMaxUnvElementNodes)
          failAt(source, lines.number, what + ": " + std::to_string(count) + " nodes (expected 1.." +
                                           std::to_string(kMaxUnvElementNodes) + ")");
        if (const UnvSolid* solid = unvSolid(element.descriptor); solid != nullptr && count != solid->nodes)
          failAt(source, lines.number, what + ": type " + std::to_string(element.descriptor) + " has " +
                                           std::to_string(solid->nodes) + " nodes, the record says " + std::to_string(count));
        if (unvBeam(element.descriptor)) {  // record 2 of a beam (3I10): orientation node, cross sections
          if (!lines.next(line) || tokens(line).size() != 3)
            failAt(source, lines.number, what + ": a beam's second record (orientation node, two cross sections) is missing");
        }
        budget.chargeBytes(std::uint64_t(count), sizeof(long long), "UNV dataset 2412: element nodes");
        budget.chargeBytes(1, sizeof(UnvElement), "UNV dataset 2412: elements");
        while (std::int64_t(elementNodes.size() - element.firstLabel) < count) {  // 8I10 per line
          if (!lines.next(line)) failAt(source, lines.number, what + ": the file ends inside its node list");
          const auto labels = tokens(line);
          if (labels.empty() || labels.size() > 8 ||
              std::int64_t(elementNodes.size() - element.firstLabel + labels.size()) > count)
            failAt(source, lines.number, what + ": expected " + std::to_string(count) + " node labels, 8 or fewer a line, got '" +
                                             std::string(line.substr(0, 60)) + "'");
          for (const std::string_view label : labels) elementNodes.push_back(unvInteger(label, source, lines.number, what));
        }
        elements.push_back(element);
      }
    } else {
      for (;;) {
        if (!lines.next(line)) failAt(source, lines.number, "dataset " + std::string(id.substr(0, 20)) + " is not closed by '-1'");
        if (trimmed(line) == "-1") break;
      }
    }
  }
  if (nodeSets == 0) failAt(source, lines.number, "no dataset 2411 (nodes)");
  points.finish();
  file.summary = std::to_string(file.points.rows()) + " nodes (dataset 2411), " + std::to_string(datasets) + " datasets";
  if (elementSets == 0) return file;
  // The elements' node labels to point rows; a solid's corners become a cell to check.
  budget.chargeBytes(nodeLabels.size(), 48, "UNV: the index of node labels");
  std::unordered_map<long long, std::int32_t> rowOf;
  rowOf.reserve(nodeLabels.size());
  for (std::size_t row = 0; row < nodeLabels.size(); ++row)
    if (!rowOf.emplace(nodeLabels[row], std::int32_t(row)).second)
      failAt(source, nodeLines[row], "dataset 2411: node label " + std::to_string(nodeLabels[row]) + " given twice");
  std::map<long long, std::int64_t> byType;
  std::array<std::int32_t, 8> corners{};
  for (const UnvElement& element : elements) {
    ++byType[element.descriptor];
    const std::size_t last = &element == &elements.back() ? elementNodes.size() : (&element + 1)->firstLabel;
    for (std::size_t k = element.firstLabel; k < last; ++k)
      if (rowOf.find(elementNodes[k]) == rowOf.end())
        failAt(source, element.line, "dataset 2412: element " + std::to_string(element.label) + ": node " +
                                         std::to_string(elementNodes[k]) + " is not in dataset 2411");
    const UnvSolid* solid = unvSolid(element.descriptor);
    if (solid == nullptr) continue;  // beams, shells and others are kept, not checked
    for (int c = 0; c < cornerCount(solid->shape); ++c)
      corners[std::size_t(c)] = rowOf.at(elementNodes[element.firstLabel + std::size_t(solid->corners[std::size_t(c)])]);
    file.cells.add(solid->shape, corners.data(), element.label);
  }
  file.hasCells = file.cells.cellCount() > 0;
  std::string types;
  for (const auto& [descriptor, count] : byType)
    types += (types.empty() ? "" : ", ") + std::to_string(count) + " of type " + std::to_string(descriptor) + " (" +
             unvKind(descriptor) + ")";
  file.summary += "\n" + std::to_string(elements.size()) + " elements (dataset 2412): " + types + "; " +
                  std::to_string(file.cells.cellCount()) + " solid cells checked";
  return file;
}

TextVolumeFile readElmerNodes(std::string bytes, const std::string& source, ReadBudget& budget) {
  TextVolumeFile file;
  file.bytes = std::move(bytes);
  PointCollector points(budget, file, "Elmer nodes");
  Lines lines{file.bytes};
  std::string_view line;
  while (lines.next(line)) {
    const auto t = tokens(line);
    if (t.empty()) continue;
    if (t.size() != 5)
      failAt(source, lines.number, "expected 'node partition x y z', got " + std::to_string(t.size()) + " fields");
    const std::string what = "node " + std::string(t[0].substr(0, 20));
    long long id = 0;
    if (std::from_chars(t[0].data(), t[0].data() + t[0].size(), id).ptr != t[0].data() + t[0].size() || id < 1)
      failAt(source, lines.number, "expected a node number >= 1, got '" + std::string(t[0].substr(0, 20)) + "'");
    double v[3];
    for (int c = 0; c < 3; ++c) {
      v[c] = parsed(t[std::size_t(2 + c)], false, source, lines.number, what);
      points.span(t[std::size_t(2 + c)]);
    }
    points.sink.add(v[0], v[1], v[2]);
  }
  if (points.sink.rows() == 0) failAt(source, lines.number, "no nodes");
  points.finish();
  file.summary = std::to_string(file.points.rows()) + " nodes";
  return file;
}

TextVolumeFile readLsDyna(std::string bytes, const std::string& source, ReadBudget& budget) {
  TextVolumeFile file;
  file.bytes = std::move(bytes);
  PointCollector points(budget, file, "LS-DYNA nodes");
  Lines lines{file.bytes};
  std::string_view line;
  bool inNodes = false;
  int keywords = 0, style = 0;  // style: 1 fixed columns, 2 comma-separated
  while (lines.next(line)) {
    if (line.empty() || line[0] == '$') continue;
    if (line[0] == '*') {
      ++keywords;
      const std::string_view keyword = trimmed(line);
      inNodes = startsWith(keyword, "*NODE") && (keyword.size() == 5 || keyword[5] == ' ');
      if (inNodes && keyword != "*NODE")
        failAt(source, lines.number, std::string(keyword.substr(0, 30)).append(
                                         ": only the standard *NODE card (I8, 3E16.0) or comma-separated nodes are supported"));
      continue;
    }
    if (!inNodes || trimmed(line).empty()) continue;
    const int lineStyle = line.find(',') != std::string_view::npos ? 2 : 1;
    if (style == 0) {
      style = lineStyle;
      file.spans.style.fixedWidth = style == 1;
    } else if (style != lineStyle) {
      failAt(source, lines.number, "a *NODE line in another layout (fixed columns and commas mixed)");
    }
    double v[3];
    if (style == 2) {
      std::vector<std::string_view> fields;
      std::size_t start = 0;
      for (;;) {
        const std::size_t comma = line.find(',', start);
        fields.push_back(trimmed(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
        if (comma == std::string_view::npos) break;
        start = comma + 1;
      }
      if (fields.size() < 4) failAt(source, lines.number, "*NODE: expected 'nid, x, y, z', got " + std::to_string(fields.size()) + " fields");
      for (int c = 0; c < 3; ++c) {
        v[c] = parsed(fields[std::size_t(1 + c)], false, source, lines.number, "*NODE " + std::string(fields[0].substr(0, 20)));
        points.span(fields[std::size_t(1 + c)]);
      }
    } else {
      // Fixed columns (LS-DYNA Keyword User's Manual, *NODE): NID 1-8, X 9-24, Y 25-40, Z 41-56.
      if (line.size() < 56)
        failAt(source, lines.number, "*NODE: a fixed-column node line needs 56 characters (NID I8, X Y Z E16.0), it has " +
                                         std::to_string(line.size()));
      for (int c = 0; c < 3; ++c) {
        const std::string_view field = line.substr(8 + 16 * std::size_t(c), 16);
        const std::string_view t = trimmed(field);
        v[c] = t.empty() ? 0.0 : parsed(t, false, source, lines.number, "*NODE " + std::string(trimmed(line.substr(0, 8))));
        points.span(field);
      }
    }
    points.sink.add(v[0], v[1], v[2]);
  }
  if (points.sink.rows() == 0) failAt(source, lines.number, "no *NODE cards");
  points.finish();
  file.summary = std::to_string(file.points.rows()) + " nodes (*NODE, " + (style == 1 ? "fixed columns" : "comma-separated") +
                 "), " + std::to_string(keywords) + " keywords";
  return file;
}

TextVolumeFile readKratos(std::string bytes, const std::string& source, ReadBudget& budget) {
  TextVolumeFile file;
  file.bytes = std::move(bytes);
  file.spans.style = {16, 'E', false, false, false};
  PointCollector points(budget, file, "Kratos nodes");
  Lines lines{file.bytes};
  std::string_view line;
  int blocks = 0, openLine = 0;
  bool inNodes = false;
  while (lines.next(line)) {
    const std::string_view t = trimmed(line);
    if (!inNodes) {
      if (startsWith(t, "Begin Nodes")) {
        inNodes = true;
        openLine = lines.number;
        ++blocks;
      }
      continue;
    }
    if (startsWith(t, "End Nodes")) {
      inNodes = false;
      continue;
    }
    if (t.empty() || startsWith(t, "//")) continue;
    const auto fields = tokens(t);
    if (fields.size() != 4) failAt(source, lines.number, "Nodes: expected 'id x y z', got " + std::to_string(fields.size()) + " fields");
    double v[3];
    for (int c = 0; c < 3; ++c) {
      v[c] = parsed(fields[std::size_t(1 + c)], false, source, lines.number, "node " + std::string(fields[0].substr(0, 20)));
      points.span(fields[std::size_t(1 + c)]);
    }
    points.sink.add(v[0], v[1], v[2]);
  }
  if (inNodes) failAt(source, openLine, "'Begin Nodes' is not closed by 'End Nodes'");
  if (blocks == 0) failAt(source, lines.number, "no 'Begin Nodes' block");
  points.finish();
  file.summary = std::to_string(file.points.rows()) + " nodes in " + std::to_string(blocks) + " 'Begin Nodes' block(s)";
  return file;
}

}  // namespace ffdkit::meshio::detail
