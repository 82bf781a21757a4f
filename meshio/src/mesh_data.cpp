#include "ffdkit/meshio/mesh_data.h"

#include <cmath>

#include <Eigen/Geometry>

namespace ffdkit::meshio {

namespace {

// Whole-matrix checks as plain loops over the coefficients: Eigen's reductions (allFinite,
// minCoeff) are left as a call per coefficient by clang under UBSan, and a mesh has millions.
bool coordinatesFinite(const Eigen::MatrixX3d& points) {
  const double* v = points.data();
  for (Eigen::Index i = 0; i < points.size(); ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

template <class Cells>
bool indicesInRange(const Cells& cells, Eigen::Index n) {
  const int* v = cells.data();
  for (Eigen::Index i = 0; i < cells.size(); ++i)
    if (v[i] < 0 || v[i] >= n) return false;
  return true;
}

}  // namespace

void validateMesh(const MeshData& mesh, const std::string& what) {
  const Eigen::Index n = mesh.points.rows();
  if (n == 0) throw MeshIoError(what + ": the mesh has no points");
  // Whole-matrix checks first; the offending row is looked for only when one fails.
  if (!coordinatesFinite(mesh.points))
    for (Eigen::Index i = 0; i < n; ++i)
      if (!mesh.points.row(i).allFinite())
        throw MeshIoError(what + ": point " + std::to_string(i) + " has a non-finite coordinate");
  auto checkIndices = [&](const auto& cells, const char* kind) {
    if (indicesInRange(cells, n)) return;
    for (Eigen::Index t = 0; t < cells.rows(); ++t)
      if (cells.row(t).minCoeff() < 0 || cells.row(t).maxCoeff() >= n)
        throw MeshIoError(what + ": " + kind + " " + std::to_string(t) + " uses a point index outside 0.." +
                          std::to_string(n - 1));
  };
  checkIndices(mesh.triangles, "triangle");
  checkIndices(mesh.segments, "segment");
}

Eigen::MatrixX3d vertexNormals(const Eigen::MatrixX3d& points, const Eigen::MatrixX3i& triangles) {
  Eigen::MatrixX3d normals = Eigen::MatrixX3d::Zero(points.rows(), 3);
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    const Eigen::Vector3d a = points.row(triangles(t, 0)), b = points.row(triangles(t, 1)), c = points.row(triangles(t, 2));
    const Eigen::RowVector3d areaNormal = (b - a).cross(c - a).transpose();  // twice the area, so larger faces weigh more
    for (int k = 0; k < 3; ++k) normals.row(triangles(t, k)) += areaNormal;
  }
  for (Eigen::Index i = 0; i < normals.rows(); ++i) {
    const double length = normals.row(i).norm();
    if (length > 0.0 && std::isfinite(length)) normals.row(i) /= length;
    else normals.row(i).setZero();
  }
  return normals;
}

}  // namespace ffdkit::meshio
