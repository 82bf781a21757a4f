#include "ffdkit/geometry/quaternion/tube_mesh.h"

#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "ffdkit/geometry/quaternion/quaternion_error.h"

namespace ffdkit::geometry::quaternion {

TriangleMesh tubeMesh(const Polyline& line, double radius, int sides) {
  const Eigen::Index n = line.points.rows();
  if (!(radius > 0.0) || sides < 3 || n < 2) {
    std::ostringstream msg;
    msg << "tubeMesh: expected radius > 0, sides >= 3 and >= 2 points, got radius " << radius << ", sides " << sides
        << ", " << n << " points";
    throw QuaternionCurveError(msg.str());
  }
  TriangleMesh mesh;
  mesh.vertices.resize(n * sides, 3);
  mesh.triangles.resize(2 * (n - 1) * sides, 3);
  const auto tangentAt = [&](Eigen::Index k) {
    const Eigen::Index a = std::max<Eigen::Index>(k - 1, 0), b = std::min<Eigen::Index>(k + 1, n - 1);
    const Eigen::Vector3d d = (line.points.row(b) - line.points.row(a)).transpose();
    return d.norm() > 0.0 ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d(Eigen::Vector3d::UnitX());
  };
  Eigen::Vector3d t = tangentAt(0);
  Eigen::Vector3d normal = t.unitOrthogonal();
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Vector3d tk = tangentAt(k);
    // Parallel transport: rotate the previous normal by the minimal rotation t -> tk.
    normal = Eigen::Quaterniond::FromTwoVectors(t, tk) * normal;
    normal = (normal - tk * tk.dot(normal)).normalized();
    t = tk;
    const Eigen::Vector3d binormal = t.cross(normal);
    for (int j = 0; j < sides; ++j) {
      const double a = 2.0 * M_PI * j / sides;
      mesh.vertices.row(k * sides + j) =
          line.points.row(k) + radius * (std::cos(a) * normal + std::sin(a) * binormal).transpose();
    }
  }
  Eigen::Index f = 0;
  for (Eigen::Index k = 0; k + 1 < n; ++k) {
    for (int j = 0; j < sides; ++j) {
      const int a = static_cast<int>(k * sides + j), b = static_cast<int>(k * sides + (j + 1) % sides);
      const int c = a + sides, d = b + sides;
      mesh.triangles.row(f++) << a, b, d;
      mesh.triangles.row(f++) << a, d, c;
    }
  }
  return mesh;
}

}  // namespace ffdkit::geometry::quaternion
