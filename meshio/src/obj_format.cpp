// Wavefront OBJ, the geometry statements: v (x y z, optionally w or r g b), f (polygons,
// fan-triangulated; "i", "i/t", "i//n", "i/t/n", negative = relative), l (poly-lines, split
// into segments). vn marks the mesh as having normals (they are recomputed on write). Texture
// and grouping statements are skipped; any other statement is an error naming it and its line.
#include <array>
#include <climits>
#include <vector>

#include "formats.h"
#include "parse_support.h"

namespace ffdkit::meshio::detail {
namespace {

bool skippedStatement(std::string_view keyword) {
  static constexpr std::string_view skipped[] = {"vt", "vp", "p", "o", "g", "s", "usemtl", "mtllib", "lod", "mg"};
  for (auto k : skipped)
    if (k == keyword) return true;
  return false;
}

// One "i", "i/t", "i//n" or "i/t/n" reference: the vertex index, 0-based; relative ones resolved
// against the vertices so far.
int vertexReference(TextCursor& text, const Where& where, long long vertices) {
  const std::string_view token = text.word();
  const std::string_view index = token.substr(0, token.find('/'));
  long long value = 0;
  const char* first = index.data();
  const char* last = index.data() + index.size();
  const auto result = std::from_chars(first, last, value);
  if (index.empty() || result.ec != std::errc() || result.ptr != last)
    text.fail(where.text() + ": expected a vertex index, got '" + std::string(token) + "'");
  const long long resolved = value < 0 ? vertices + value : value - 1;
  if (value == 0 || resolved < 0 || resolved >= vertices)
    text.fail(where.text() + ": vertex index " + std::string(index) + " is outside " +
              (vertices == 0 ? std::string("the vertices (none so far)") : "1.." + std::to_string(vertices) +
                                                                               " (or -1..-" + std::to_string(vertices) + ")"));
  // The texture and normal parts must be integers too (not checked against their lists).
  for (std::size_t slash = token.find('/'); slash != std::string_view::npos; slash = token.find('/', slash + 1)) {
    const std::size_t end = std::min(token.find('/', slash + 1), token.size());
    const std::string_view part = token.substr(slash + 1, end - slash - 1);
    long long ignored = 0;
    const auto r = std::from_chars(part.data(), part.data() + part.size(), ignored);
    if (!part.empty() && (r.ec != std::errc() || r.ptr != part.data() + part.size()))
      text.fail(where.text() + ": malformed vertex reference '" + std::string(token) + "'");
  }
  return int(resolved);
}

}  // namespace

MeshData readObj(std::string_view bytes, const std::string& source, ReadBudget& budget) {
  TextCursor text(bytes, source);
  PointSink points(0, &budget, "OBJ vertices");
  TriangleSink triangles(0, &budget, "OBJ faces (their triangles)");
  SegmentSink segments(0, &budget, "OBJ lines (their segments)");
  MeshData mesh;
  long long faces = 0, lines = 0;
  std::vector<int> polygon;
  // The budget's refusal names the statement's line.
  try {
    while (!text.atEnd()) {
      text.skipBlanks();
      if (text.atLineEnd(true)) {
        text.nextLine();
        continue;
      }
      const std::string_view keyword = text.word();
      if (keyword == "v") {
        if (points.rows() == INT_MAX) text.fail("more vertices than ffdkit indexes");
        const Where where{"vertex", points.rows()};
        const double x = text.number(where), y = text.number(where), z = text.number(where);
        // An optional w, or an r g b colour: numbers too, and nothing else.
        for (int extra = 0; extra < 3; ++extra) {
          text.skipBlanks();
          if (text.atLineEnd(true)) break;
          (void)text.number(where);
        }
        points.add(x, y, z);
        text.endLine(where, true);
      } else if (keyword == "vn") {
        mesh.hasNormals = true;
        text.nextLine();
      } else if (keyword == "f" || keyword == "l") {
        const bool face = keyword == "f";
        const Where where{face ? "face" : "line", face ? faces : lines};
        polygon.clear();
        for (;;) {
          text.skipBlanks();
          if (text.atLineEnd(true)) break;
          polygon.push_back(vertexReference(text, where, points.rows()));
        }
        if (face) {
          if (polygon.size() < 3) text.fail(where.text() + ": a face needs at least 3 vertices, it has " + std::to_string(polygon.size()));
          for (std::size_t k = 1; k + 1 < polygon.size(); ++k) triangles.add(polygon[0], polygon[k], polygon[k + 1]);
          ++faces;
        } else {
          if (polygon.size() < 2) text.fail(where.text() + ": a line needs at least 2 vertices, it has " + std::to_string(polygon.size()));
          for (std::size_t k = 0; k + 1 < polygon.size(); ++k) segments.add(polygon[k], polygon[k + 1]);
          ++lines;
        }
        text.nextLine();
      } else if (skippedStatement(keyword)) {
        text.nextLine();
      } else {
        text.fail("unknown statement '" + std::string(keyword.substr(0, 40)) + "'");
      }
    }
  } catch (const ReadLimitError& e) {
    text.fail(e.what());
  }
  if (points.rows() == 0) throw MeshIoError(source + ": the file has no vertices");
  mesh.points = points.take();
  mesh.triangles = triangles.take();
  mesh.segments = segments.take();
  return mesh;
}

void writeObj(ByteSink& out, const MeshData& mesh) {
  const bool normals = mesh.hasNormals && mesh.triangles.rows() > 0;
  out.write("# ffdkit\n");
  auto rows = [&](std::string_view keyword, const Eigen::MatrixX3d& m) {
    writeRows(out, m.rows(), keyword.size() + 3 * 25, [&](char* at, Eigen::Index i) {
      at = std::copy(keyword.begin(), keyword.end(), at);
      for (int c = 0; c < 3; ++c) {
        *at++ = ' ';
        at = putNumber(at, m(i, c));
      }
      *at++ = '\n';
      return at;
    });
  };
  rows("v", mesh.points);
  if (normals) rows("vn", vertexNormals(mesh.points, mesh.triangles));
  // "f a b c" or "f a//a b//b c//c": 1-based indices of at most 11 digits each.
  writeRows(out, mesh.triangles.rows(), 2 + 3 * (normals ? 25 : 12), [&](char* at, Eigen::Index t) {
    *at++ = 'f';
    for (int c = 0; c < 3; ++c) {
      const long long index = mesh.triangles(t, c) + 1LL;
      *at++ = ' ';
      at = std::to_chars(at, at + 12, index).ptr;
      if (normals) {
        *at++ = '/';
        *at++ = '/';
        at = std::to_chars(at, at + 12, index).ptr;
      }
    }
    *at++ = '\n';
    return at;
  });
  writeRows(out, mesh.segments.rows(), 2 + 2 * 12 + 1, [&](char* at, Eigen::Index s) {
    *at++ = 'l';
    for (int c = 0; c < 2; ++c) {
      *at++ = ' ';
      at = std::to_chars(at, at + 12, mesh.segments(s, c) + 1LL).ptr;
    }
    *at++ = '\n';
    return at;
  });
}

}  // namespace ffdkit::meshio::detail
