#include "ffdkit/cad/tessellation.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <queue>
#include <unordered_map>
#include <utility>
#include <vector>

#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Tool.hxx>
#include <Poly_Triangulation.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>

#include "cad_model_data.h"

namespace ffdkit::cad {

namespace {

constexpr std::size_t kMaxTriangles = 20'000'000;

struct PointHash {
  std::size_t operator()(const Eigen::Vector3d& p) const {
    std::uint64_t h = 1469598103934665603ull;
    for (int i = 0; i < 3; ++i) h = (h ^ std::bit_cast<std::uint64_t>(p[i] + 0.0)) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};

/// The triangles of all faces, each face with its own points (as tessellate returns them).
struct FaceTriangles {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3i> triangles;
  std::vector<int> parts;  ///< per triangle
  std::vector<int> faces;  ///< per triangle
};

/// Bisects every edge longer than `maxLength`, longest first, in every triangle that has it.
/// Points with the same coordinates are one point for the edges (faces have their own copies of
/// their boundary's points), so an edge between two faces is split in both and no crack opens.
void splitLongEdges(FaceTriangles& mesh, double maxLength) {
  // One id per distinct coordinate: the edges' ends.
  std::unordered_map<Eigen::Vector3d, int, PointHash> idOf;
  std::vector<Eigen::Vector3d> distinct;
  std::vector<int> canon(mesh.points.size());
  for (std::size_t i = 0; i < mesh.points.size(); ++i) {
    const auto [it, added] = idOf.try_emplace(mesh.points[i], static_cast<int>(distinct.size()));
    if (added) distinct.push_back(mesh.points[i]);
    canon[i] = it->second;
  }
  const auto key = [](int a, int b) {
    return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint32_t>(std::max(a, b));
  };
  std::unordered_map<std::uint64_t, std::vector<int>> trianglesOf;
  std::priority_queue<std::pair<double, std::uint64_t>> longest;
  const auto length = [&](int a, int b) { return (distinct[a] - distinct[b]).norm(); };
  const auto note = [&](int a, int b, int triangle) {
    std::vector<int>& list = trianglesOf[key(a, b)];
    if (list.empty() && length(a, b) > maxLength) longest.emplace(length(a, b), key(a, b));
    list.push_back(triangle);
  };
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int e = 0; e < 3; ++e)
      note(canon[mesh.triangles[t][e]], canon[mesh.triangles[t][(e + 1) % 3]], static_cast<int>(t));
  while (!longest.empty()) {
    const std::uint64_t edge = longest.top().second;
    longest.pop();
    const auto found = trianglesOf.find(edge);
    if (found == trianglesOf.end()) continue;  // split already
    const std::vector<int> sharing = std::move(found->second);
    trianglesOf.erase(found);
    if (mesh.triangles.size() + sharing.size() > kMaxTriangles)
      throw CadError("tessellation: maxEdgeLength " + std::to_string(maxLength) + " would make more than " +
                     std::to_string(kMaxTriangles) + " triangles");
    const int u = static_cast<int>(edge >> 32), v = static_cast<int>(edge & 0xffffffffu);
    const Eigen::Vector3d middle = 0.5 * (distinct[u] + distinct[v]);
    const int m = static_cast<int>(distinct.size());
    distinct.push_back(middle);
    std::unordered_map<int, int> pointOfFace;  // each face its own copy of the midpoint
    for (const int t : sharing) {
      Eigen::Vector3i corners = mesh.triangles[t];
      int at = 0;  // corners (at, at+1) are the edge
      while (at < 3 && key(canon[corners[at]], canon[corners[(at + 1) % 3]]) != edge) ++at;
      if (at == 3) continue;  // a degenerate triangle that had the edge twice: split once
      const int x = corners[at], y = corners[(at + 1) % 3], z = corners[(at + 2) % 3];
      auto [copy, added] = pointOfFace.try_emplace(mesh.faces[t], static_cast<int>(mesh.points.size()));
      if (added) {
        mesh.points.push_back(middle);
        canon.push_back(m);
      }
      const int mid = copy->second;
      const int other = static_cast<int>(mesh.triangles.size());
      mesh.triangles[t] = Eigen::Vector3i(x, mid, z);
      mesh.triangles.emplace_back(mid, y, z);
      mesh.parts.push_back(mesh.parts[t]);
      mesh.faces.push_back(mesh.faces[t]);
      std::vector<int>& yz = trianglesOf[key(canon[y], canon[z])];
      std::replace(yz.begin(), yz.end(), t, other);
      note(canon[x], m, t);
      note(m, canon[y], other);
      note(m, canon[z], t);
      note(m, canon[z], other);
    }
  }
}

}  // namespace

CadTriangles tessellate(const CadModel& model, const TessellationOptions& options) {
  double linear = options.linearDeflection;
  if (linear == 0.0) linear = 1e-3 * std::max(model.bounds().diagonal().norm(), 1e-300);
  if (!(linear > 0.0) || !std::isfinite(linear))
    throw CadError("tessellation: linearDeflection must be > 0 and finite, got " + std::to_string(options.linearDeflection));
  if (!(options.angularDeflection > 0.0) || !std::isfinite(options.angularDeflection))
    throw CadError("tessellation: angularDeflection must be > 0 and finite, got " + std::to_string(options.angularDeflection));
  if (!(options.maxEdgeLength >= 0.0) || !std::isfinite(options.maxEdgeLength))
    throw CadError("tessellation: maxEdgeLength must be >= 0 and finite, got " + std::to_string(options.maxEdgeLength));
  FaceTriangles all;
  std::vector<Eigen::Vector3d>& points = all.points;
  std::vector<Eigen::Vector3i>& triangles = all.triangles;
  std::vector<int>& parts = all.parts;
  int faceCount = 0;
  const auto& data = model.data();
  for (int p = 0; p < static_cast<int>(data.parts.size()); ++p) {
    const auto& part = data.parts[p];
    guardOcct("tessellating part '" + part.name + "'", [&] {
      BRepMesh_IncrementalMesh mesher(part.shape, linear, false, options.angularDeflection, false);
      for (TopExp_Explorer it(part.shape, TopAbs_FACE); it.More(); it.Next()) {
        const TopoDS_Face& face = TopoDS::Face(it.Current());
        TopLoc_Location location;
        const Handle(Poly_Triangulation) mesh = BRep_Tool::Triangulation(face, location);
        if (mesh.IsNull()) continue;
        const gp_Trsf placement = location.Transformation();
        const int base = static_cast<int>(points.size());
        for (Standard_Integer i = 1; i <= mesh->NbNodes(); ++i) {
          const gp_Pnt node = mesh->Node(i).Transformed(placement);
          points.emplace_back(node.X(), node.Y(), node.Z());
        }
        const bool reversed = face.Orientation() == TopAbs_REVERSED;
        for (Standard_Integer i = 1; i <= mesh->NbTriangles(); ++i) {
          Standard_Integer a, b, c;
          mesh->Triangle(i).Get(a, b, c);
          if (reversed) std::swap(b, c);
          triangles.emplace_back(base + a - 1, base + b - 1, base + c - 1);
          parts.push_back(p);
          all.faces.push_back(faceCount);
        }
        ++faceCount;
      }
    });
  }
  if (options.maxEdgeLength > 0.0) splitLongEdges(all, options.maxEdgeLength);
  CadTriangles out;
  out.points.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) out.points.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  out.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t i = 0; i < triangles.size(); ++i)
    out.triangles.row(static_cast<Eigen::Index>(i)) = triangles[i].transpose();
  out.partOfTriangle = Eigen::Map<const Eigen::VectorXi>(parts.data(), static_cast<Eigen::Index>(parts.size()));
  return out;
}

double enclosedVolume(const Eigen::MatrixX3d& points, const Eigen::MatrixX3i& triangles) {
  double sum = 0.0;
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    const Eigen::Vector3d a = points.row(triangles(t, 0)).transpose();
    const Eigen::Vector3d b = points.row(triangles(t, 1)).transpose();
    const Eigen::Vector3d c = points.row(triangles(t, 2)).transpose();
    sum += a.dot(b.cross(c));
  }
  return sum / 6.0;
}

}  // namespace ffdkit::cad
