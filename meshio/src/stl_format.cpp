// STL, binary (80-byte header, a triangle count, 50 bytes per triangle) and ASCII (solid /
// facet normal / outer loop / vertex x3 / endloop / endfacet / endsolid). STL stores every
// triangle's corners on their own: identical corners are merged into one point, so the mesh is
// connected again (and deforms and shades as one surface).
#include <climits>
#include <cstring>
#include <unordered_map>

#include <Eigen/Geometry>

#include "formats.h"
#include "parse_support.h"

namespace ffdkit::meshio::detail {
namespace {

struct Corner {
  double x, y, z;
  bool operator==(const Corner& o) const {
    return std::memcmp(this, &o, sizeof(Corner)) == 0;  // bitwise: -0.0 and 0.0 stay apart, as written
  }
};
struct CornerHash {
  std::size_t operator()(const Corner& c) const {
    std::uint64_t bits[3];
    std::memcpy(bits, &c, sizeof bits);
    std::uint64_t h = 1469598103934665603ULL;
    for (auto b : bits) h = (h ^ b) * 1099511628211ULL ^ (b >> 29);
    return std::size_t(h);
  }
};

// Corners to shared points. The budget pays for the points, the triangles and the index of
// corners (a hash node and a bucket per point, kIndexBytesPerPoint).
class CornerMerger {
 public:
  static constexpr std::uint64_t kIndexBytesPerPoint = sizeof(std::pair<const Corner, int>) + 2 * sizeof(void*) + sizeof(void*);

  CornerMerger(Eigen::Index triangles, ReadBudget& budget)
      : points_(triangles, &budget, "STL corners (merged into points)", kIndexBytesPerPoint),
        triangles_(triangles, &budget, "STL triangles") {
    index_.reserve(std::size_t(triangles));  // buckets: at most 8 bytes per 50 of the file
  }
  int point(const Corner& c) {
    const auto [it, added] = index_.try_emplace(c, int(points_.rows()));
    if (added) points_.add(c.x, c.y, c.z);
    return it->second;
  }
  void triangle(int a, int b, int c) { triangles_.add(a, b, c); }
  MeshData take() {
    MeshData mesh;
    mesh.points = points_.take();
    mesh.triangles = triangles_.take();
    return mesh;
  }

 private:
  std::unordered_map<Corner, int, CornerHash> index_;
  PointSink points_;
  TriangleSink triangles_;
};

bool looksAscii(std::string_view bytes) {
  std::size_t i = 0;
  while (i < bytes.size() && (bytes[i] == ' ' || bytes[i] == '\t' || bytes[i] == '\r' || bytes[i] == '\n')) ++i;
  return bytes.substr(i, 5) == "solid";
}

MeshData readBinaryStl(std::string_view bytes, const std::string& source, ReadBudget& budget) {
  ByteCursor data(bytes, source);
  data.need(84, {"header"});
  data.skip(80);
  const std::uint64_t count = data.take<std::uint32_t>(false);
  const std::uint64_t expected = 84 + kStlTriangleBytes * count;
  if (expected != bytes.size())
    data.fail("announces " + std::to_string(count) + " triangles (" + std::to_string(expected) + " bytes), the file has " +
              std::to_string(bytes.size()) + " bytes");
  if (count == 0) data.fail("the file has no triangles");
  if (3 * count > std::uint64_t(INT_MAX)) data.fail(std::to_string(count) + " triangles is more than ffdkit indexes");
  CornerMerger merger(Eigen::Index(count), budget);
  for (std::uint64_t t = 0; t < count; ++t) {
    data.skip(12);  // the facet normal: recomputed from the corners when written
    int ids[3];
    for (int& id : ids) {
      Corner c;
      c.x = data.take<float>(false);
      c.y = data.take<float>(false);
      c.z = data.take<float>(false);
      if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z))
        data.fail(Where{"triangle", (long long)t}.text() + ": non-finite coordinate");
      id = merger.point(c);
    }
    data.skip(2);  // attribute byte count
    merger.triangle(ids[0], ids[1], ids[2]);
  }
  return merger.take();
}

void expectWord(TextCursor& text, std::string_view word, const Where& where) {
  const std::string_view got = text.word();
  if (got != word) text.fail(where.text() + ": expected '" + std::string(word) + "', got '" + std::string(got.substr(0, 40)) + "'");
}

MeshData readAsciiStl(std::string_view bytes, const std::string& source, ReadBudget& budget) {
  TextCursor text(bytes, source);
  // Each facet takes well over 50 characters: a cheap bound for the first allocation.
  CornerMerger merger(Eigen::Index(bytes.size() / 64), budget);
  long long t = 0;
  auto nextWord = [&]() -> std::string_view {
    for (;;) {
      text.skipBlanks();
      if (text.atEnd()) return {};
      if (!text.atLineEnd()) return text.word();
      text.nextLine();
    }
  };
  std::string_view word = nextWord();
  while (word == "solid") {
    text.nextLine();  // the solid's name
    for (word = nextWord(); word == "facet"; word = nextWord(), ++t) {
      const Where where{"triangle", t};
      if (t >= INT_MAX / 3) text.fail("more triangles than ffdkit indexes");
      expectWord(text, "normal", where);
      for (int k = 0; k < 3; ++k) (void)text.number(where);
      if (nextWord() != "outer") text.fail(where.text() + ": expected 'outer loop'");
      int ids[3];
      expectWord(text, "loop", where);
      for (int& id : ids) {
        if (nextWord() != "vertex") text.fail(where.text() + ": expected 'vertex'");
        Corner c{text.number(where), text.number(where), text.number(where)};
        id = merger.point(c);
      }
      if (nextWord() != "endloop") text.fail(where.text() + ": expected 'endloop'");
      if (nextWord() != "endfacet") text.fail(where.text() + ": expected 'endfacet'");
      merger.triangle(ids[0], ids[1], ids[2]);
    }
    if (word != "endsolid") text.fail("expected 'facet' or 'endsolid', got '" + std::string(word.substr(0, 40)) + "'");
    text.nextLine();  // the solid's name again
    word = nextWord();
  }
  if (!word.empty()) text.fail("expected 'solid', got '" + std::string(word.substr(0, 40)) + "'");
  if (t == 0) throw MeshIoError(source + ": the file has no triangles");
  return merger.take();
}

}  // namespace

MeshData readStl(std::string_view bytes, const std::string& source, ReadBudget& budget) {
  // A binary file may also start with "solid": its size decides first.
  if (bytes.size() >= 84) {
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    if (84 + kStlTriangleBytes * std::uint64_t(count) == bytes.size()) return readBinaryStl(bytes, source, budget);
  }
  return looksAscii(bytes) ? readAsciiStl(bytes, source, budget) : readBinaryStl(bytes, source, budget);
}

void writeStl(ByteSink& sink, const MeshData& mesh) {
  if (mesh.triangles.rows() == 0) throw MeshIoError("STL needs triangles");
  std::string header(80, '\0');
  std::memcpy(header.data(), "ffdkit binary STL", 17);
  appendBinary(header, std::uint32_t(mesh.triangles.rows()), false);
  BinaryChunks chunks(sink);
  chunks.bytes(header);
  chunks.records(mesh.triangles.rows(), kStlTriangleBytes, [&](char* at, Eigen::Index t) {
    const Eigen::RowVector3d a = mesh.points.row(mesh.triangles(t, 0));
    const Eigen::RowVector3d b = mesh.points.row(mesh.triangles(t, 1));
    const Eigen::RowVector3d c = mesh.points.row(mesh.triangles(t, 2));
    const Eigen::RowVector3d n = (b - a).cross(c - a).normalized();
    for (int k = 0; k < 3; ++k) at = storeBinary(at, std::isfinite(n[k]) ? float(n[k]) : 0.0f, false);
    for (const auto* p : {&a, &b, &c})
      for (int k = 0; k < 3; ++k) at = storeBinary(at, float((*p)[k]), false);
    storeBinary(at, std::uint16_t(0), false);
  });
  chunks.flush();
}

}  // namespace ffdkit::meshio::detail
