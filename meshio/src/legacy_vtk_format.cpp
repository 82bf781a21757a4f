// Legacy VTK poly data (.vtk), read by ffdkit: VTK's own reader trusts the cell counts in the
// file (a wrong one crashed it under fuzzing), so this reader checks them while it parses.
// ASCII and BINARY (big-endian), POINTS, then VERTICES / LINES / POLYGONS / TRIANGLE_STRIPS in
// the classic layout (n, size, then "count id id ...") or the 5.x layout (OFFSETS and
// CONNECTIVITY arrays). POINT_DATA, CELL_DATA and FIELD end the geometry (only NORMALS is noted).
#include <algorithm>
#include <climits>
#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

#include "formats.h"
#include "parse_support.h"

namespace ffdkit::meshio::detail {
namespace {

class LegacyCursor {
 public:
  LegacyCursor(std::string_view bytes, const std::string& source) : bytes_(bytes), source_(source) {}

  bool binary = false;

  std::string_view line() {
    const std::size_t end = std::min(bytes_.find('\n', pos_), bytes_.size());
    const std::string_view text = bytes_.substr(pos_, end - pos_);
    pos_ = std::min(end + 1, bytes_.size());
    ++line_;
    return text;
  }
  // The next token, across newlines; empty at the end.
  std::string_view word() {
    for (;;) {
      while (pos_ < bytes_.size() && (bytes_[pos_] == ' ' || bytes_[pos_] == '\t' || bytes_[pos_] == '\r')) ++pos_;
      if (pos_ < bytes_.size() && bytes_[pos_] == '\n') {
        ++pos_;
        ++line_;
        continue;
      }
      break;
    }
    const std::size_t start = pos_;
    while (pos_ < bytes_.size() && !TextCursor::isBlankOrNewline(bytes_[pos_])) ++pos_;
    return bytes_.substr(start, pos_ - start);
  }
  long long count(const Where& where) {
    const std::string_view w = word();
    long long value = -1;
    const auto r = std::from_chars(w.data(), w.data() + w.size(), value);
    if (w.empty() || r.ec != std::errc() || r.ptr != w.data() + w.size() || value < 0)
      fail(where.text() + ": expected a count, got '" + std::string(w.substr(0, 40)) + "'");
    return value;
  }
  // Binary data start after the end of the keyword's line.
  void startBinary() {
    while (pos_ < bytes_.size() && bytes_[pos_] != '\n') ++pos_;
    if (pos_ < bytes_.size()) ++pos_, ++line_;
  }
  std::size_t bytesLeft() const { return bytes_.size() - pos_; }
  /// Where the cursor is, to look ahead and come back.
  std::pair<std::size_t, int> mark() const { return {pos_, line_}; }
  void reset(std::pair<std::size_t, int> at) { std::tie(pos_, line_) = at; }

  // One value of `type` ("float", "double", "int", "vtktypeint64", ...) as double.
  double value(std::string_view type, const Where& where) {
    if (!binary) {
      const std::string_view w = word();
      TextCursor text(w, source_, line_);
      return text.number(where);
    }
    const std::size_t size = sizeOf(type);
    if (size > bytesLeft()) fail(where.text() + ": the file ends early");
    ByteCursor data(bytes_, source_, pos_);
    pos_ += size;
    if (type == "float") return data.take<float>(true);
    if (type == "double") return data.take<double>(true);
    if (size == 8) return double(data.take<std::int64_t>(true));
    return double(data.take<std::int32_t>(true));
  }

  // A value that must be an integer (an offset, a count, a point id): whole and within +-2^53,
  // before any conversion to an integer type.
  long long integer(std::string_view type, const Where& where) {
    const double v = value(type, where);
    if (!(std::abs(v) <= 9007199254740992.0) || v != std::floor(v)) fail(where.text() + ": expected an integer, got " + std::to_string(v));
    return (long long)v;
  }

  static std::size_t sizeOf(std::string_view type) {
    if (type == "double" || type == "vtktypeint64" || type == "long" || type == "vtktypeuint64") return 8;
    return 4;
  }
  static bool known(std::string_view type, bool real) {
    if (real) return type == "float" || type == "double";
    return type == "int" || type == "vtktypeint32" || type == "vtktypeint64" || type == "vtkIdType" || type == "long";
  }

  [[noreturn]] void fail(const std::string& message) const {
    throw MeshIoError(source_ + ":" + std::to_string(line_) + ": " + message);
  }

 private:
  std::string_view bytes_;
  const std::string& source_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

// Calls `cell(ids, size, index)` for each cell, its point ids checked against `points`. The
// section's values are held while they are read (charged to `budget`, given back after).
template <class Cell>
void readCells(LegacyCursor& in, const char* kind, long long points, ReadBudget& budget, Cell&& onCell) {
  const long long first = in.count({kind}), second = in.count({kind});
  const std::size_t minimum = in.binary ? 4 : 2;
  auto checkFits = [&](long long n) {
    // ASCII: a digit and a separator per value (the last value may end the file).
    if (std::size_t(n) > (in.bytesLeft() + 1) / minimum)
      in.fail(std::string(kind) + ": " + std::to_string(n) + " values do not fit in the " + std::to_string(in.bytesLeft()) +
              " bytes left");
  };
  auto id = [&](long long value, long long cell) {
    if (value < 0 || value >= points)
      in.fail(Where{kind, cell}.text() + ": point id " + std::to_string(value) + " is outside 0.." + std::to_string(points - 1));
    return int(value);
  };
  const auto start = in.mark();
  if (in.word() == "OFFSETS") {
    // 5.x: `first` offsets (cells + 1) and `second` connectivity entries.
    const std::string_view offsetType = in.word();
    if (!LegacyCursor::known(offsetType, false)) in.fail(std::string(kind) + ": unknown OFFSETS type '" + std::string(offsetType) + "'");
    checkFits(first);
    if (in.binary) in.startBinary();
    budget.chargeBytes(std::uint64_t(first), sizeof(long long), std::string(kind) + " offsets");
    std::vector<long long> offsets(static_cast<std::size_t>(first));
    for (long long k = 0; k < first; ++k) offsets[std::size_t(k)] = in.integer(offsetType, {kind, -1, "offsets"});
    if (in.word() != "CONNECTIVITY") in.fail(std::string(kind) + ": expected CONNECTIVITY");
    const std::string_view idType = in.word();
    if (!LegacyCursor::known(idType, false)) in.fail(std::string(kind) + ": unknown CONNECTIVITY type '" + std::string(idType) + "'");
    checkFits(second);
    if (in.binary) in.startBinary();
    if (first > 0 && (offsets[0] != 0 || offsets.back() != second))
      in.fail(std::string(kind) + ": the offsets do not run from 0 to " + std::to_string(second));
    budget.chargeBytes(std::uint64_t(second), sizeof(int), std::string(kind) + " connectivity");
    std::vector<int> connectivity(static_cast<std::size_t>(second));
    for (long long k = 0; k < second; ++k) connectivity[std::size_t(k)] = id(in.integer(idType, {kind, -1, "connectivity"}), -1);
    for (long long c = 0; c + 1 < first; ++c) {
      const long long a = offsets[std::size_t(c)], b = offsets[std::size_t(c + 1)];
      if (b < a || b > second) in.fail(Where{kind, c}.text() + ": offset " + std::to_string(b) + " out of order");
      onCell(connectivity.data() + a, std::size_t(b - a), c);
    }
    budget.releaseBytes(std::uint64_t(first) * sizeof(long long) + std::uint64_t(second) * sizeof(int));
    return;
  }
  // Classic: `first` cells in `second` integers, each cell "count id id ...".
  in.reset(start);
  checkFits(second);
  if (in.binary) in.startBinary();
  budget.chargeBytes(std::uint64_t(second), sizeof(long long), std::string(kind) + " cell list");
  std::vector<long long> values;
  values.reserve(std::size_t(second));
  while ((long long)values.size() < second) values.push_back(in.integer("int", {kind}));
  std::vector<int> ids;
  std::size_t k = 0;
  for (long long c = 0; c < first; ++c) {
    if (k >= values.size()) in.fail(Where{kind, c}.text() + ": the cell list ends early (" + std::to_string(second) + " values)");
    const long long n = values[k++];
    if (n < 0 || std::size_t(n) > values.size() - k)
      in.fail(Where{kind, c}.text() + ": " + std::to_string(n) + " points run past the cell list");
    ids.clear();
    for (long long j = 0; j < n; ++j) ids.push_back(id(values[k++], c));
    onCell(ids.data(), ids.size(), c);
  }
  if (k != values.size()) in.fail(std::string(kind) + ": " + std::to_string(values.size() - k) + " values after the last cell");
  budget.releaseBytes(std::uint64_t(second) * sizeof(long long));
}

}  // namespace

MeshData readLegacyVtk(std::string_view bytes, const std::string& source, ReadBudget& budget) {
  LegacyCursor in(bytes, source);
  if (in.line().substr(0, 22) != "# vtk DataFile Version") in.fail("not a legacy VTK file (no '# vtk DataFile Version' line)");
  (void)in.line();  // the title
  const std::string_view encoding = in.word();
  if (encoding == "BINARY") in.binary = true;
  else if (encoding != "ASCII") in.fail("expected ASCII or BINARY, got '" + std::string(encoding.substr(0, 40)) + "'");
  if (in.word() != "DATASET") in.fail("expected DATASET");
  const std::string_view dataset = in.word();
  if (dataset != "POLYDATA") in.fail("only POLYDATA data sets are read, got '" + std::string(dataset.substr(0, 40)) + "'");

  MeshData mesh;
  TriangleSink triangles(0, &budget, "POLYGONS and TRIANGLE_STRIPS (their triangles)");
  SegmentSink segments(0, &budget, "LINES (their segments)");
  bool havePoints = false;
  std::vector<std::string_view> cellSections;  // each read once: VTK's reader keeps only the last
  // The budget's refusal names the line of the section.
  try {
    for (std::string_view keyword = in.word(); !keyword.empty(); keyword = in.word()) {
      if (keyword == "POINTS") {
        if (havePoints) in.fail("a second POINTS section");
        const long long n = in.count({"POINTS"});
        const std::string_view type = in.word();
        if (!LegacyCursor::known(type, true)) in.fail("POINTS: unknown type '" + std::string(type.substr(0, 40)) + "'");
        if (n == 0) in.fail("the file has no points");
        if (n > INT_MAX || std::size_t(n) > in.bytesLeft() / (3 * (in.binary ? LegacyCursor::sizeOf(type) : 2)))
          in.fail("POINTS: " + std::to_string(n) + " points do not fit in the " + std::to_string(in.bytesLeft()) + " bytes left");
        if (in.binary) in.startBinary();
        budget.chargePoints(std::uint64_t(n), "POINTS");
        mesh.points.resize(Eigen::Index(n), 3);
        for (long long i = 0; i < n; ++i)
          for (int c = 0; c < 3; ++c) {
            const double v = in.value(type, {"point", i});
            if (!std::isfinite(v)) in.fail(Where{"point", i}.text() + ": non-finite coordinate");
            mesh.points(i, c) = v;
          }
        havePoints = true;
      } else if (keyword == "VERTICES" || keyword == "LINES" || keyword == "POLYGONS" || keyword == "TRIANGLE_STRIPS") {
        if (!havePoints) in.fail(std::string(keyword) + " before POINTS");
        if (std::find(cellSections.begin(), cellSections.end(), keyword) != cellSections.end())
          in.fail("a second " + std::string(keyword) + " section");
        cellSections.push_back(keyword);
        const char* kind = keyword == "VERTICES" ? "vertex cell" : keyword == "LINES" ? "line" : keyword == "POLYGONS" ? "polygon" : "strip";
        // A cell too short to give a segment or a triangle is an error, not a silent drop.
        const std::size_t fewest = keyword == "VERTICES" ? 1 : keyword == "LINES" ? 2 : 3;
        readCells(in, kind, mesh.points.rows(), budget, [&](const int* cell, std::size_t size, long long index) {
          if (size < fewest)
            in.fail(Where{kind, index}.text() + ": needs at least " + std::to_string(fewest) + " points, it has " + std::to_string(size));
          if (keyword == "LINES") {
            for (std::size_t k = 0; k + 1 < size; ++k) segments.add(cell[k], cell[k + 1]);
          } else if (keyword == "POLYGONS") {
            for (std::size_t k = 1; k + 1 < size; ++k) triangles.add(cell[0], cell[k], cell[k + 1]);
          } else if (keyword == "TRIANGLE_STRIPS") {
            for (std::size_t k = 0; k + 2 < size; ++k) {
              if (k % 2 == 0) triangles.add(cell[k], cell[k + 1], cell[k + 2]);
              else triangles.add(cell[k + 1], cell[k], cell[k + 2]);
            }
          }
        });
      } else if (keyword == "METADATA") {
        // Array information: lines up to the next blank line.
        for (std::string_view l = in.line(); in.bytesLeft() > 0;) {
          l = in.line();
          if (l.find_first_not_of(" \t\r") == std::string_view::npos) break;
        }
      } else if (keyword == "POINT_DATA" || keyword == "CELL_DATA" || keyword == "FIELD") {
        // Attributes are not read; only whether the points have normals.
        mesh.hasNormals = keyword == "POINT_DATA" && bytes.find("\nNORMALS ") != std::string_view::npos;
        break;
      } else {
        in.fail("unknown section '" + std::string(keyword.substr(0, 40)) + "'");
      }
    }
  } catch (const ReadLimitError& e) {
    in.fail(e.what());
  }
  if (!havePoints) throw MeshIoError(source + ": the file has no points");
  mesh.triangles = triangles.take();
  mesh.segments = segments.take();
  return mesh;
}

}  // namespace ffdkit::meshio::detail
