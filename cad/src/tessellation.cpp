#include "ffdkit/cad/tessellation.h"

#include <cmath>
#include <vector>

#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Tool.hxx>
#include <Poly_Triangulation.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>

#include "cad_model_data.h"

namespace ffdkit::cad {

CadTriangles tessellate(const CadModel& model, const TessellationOptions& options) {
  double linear = options.linearDeflection;
  if (linear == 0.0) linear = 1e-3 * std::max(model.bounds().diagonal().norm(), 1e-300);
  if (!(linear > 0.0) || !std::isfinite(linear))
    throw CadError("tessellation: linearDeflection must be > 0 and finite, got " + std::to_string(options.linearDeflection));
  if (!(options.angularDeflection > 0.0) || !std::isfinite(options.angularDeflection))
    throw CadError("tessellation: angularDeflection must be > 0 and finite, got " + std::to_string(options.angularDeflection));
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3i> triangles;
  std::vector<int> parts;
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
        }
      }
    });
  }
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
