#include "ffdkit/widgets/ray.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace ffdkit::widgets {

std::optional<RaySegmentHit> closestRaySegment(const Ray& ray, const Eigen::Vector3d& a,
                                               const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = ray.direction.normalized();
  const Eigen::Vector3d u = b - a;
  const Eigen::Vector3d w = ray.origin - a;
  const double uu = u.squaredNorm();
  double s = 0.0, t = 0.0;
  if (uu <= 0.0) {
    t = std::max(0.0, -w.dot(d));
  } else {
    const double ud = u.dot(d);
    const double denom = uu - ud * ud;  // |u|^2 |d|^2 - (u.d)^2, |d| = 1
    s = denom > 1e-14 * uu ? (u.dot(w) - ud * d.dot(w)) / denom : 0.0;
    s = std::clamp(s, 0.0, 1.0);
    t = (a + s * u - ray.origin).dot(d);
    if (t < 0.0) {
      t = 0.0;
      s = std::clamp((ray.origin - a).dot(u) / uu, 0.0, 1.0);
    }
  }
  const Eigen::Vector3d pr = ray.origin + t * d;
  const Eigen::Vector3d ps = a + s * u;
  return RaySegmentHit{t, s, (pr - ps).norm()};
}

std::optional<double> closestLineParameter(const Ray& ray, const Eigen::Vector3d& origin,
                                           const Eigen::Vector3d& axis) {
  const Eigen::Vector3d d = ray.direction.normalized();
  const Eigen::Vector3d a = axis.normalized();
  const double b = a.dot(d);
  const double denom = 1.0 - b * b;
  if (denom < 1e-12) return std::nullopt;
  const Eigen::Vector3d w = origin - ray.origin;
  // Minimise |origin + s a - (ray.origin + t d)| over s, t.
  return (b * d.dot(w) - a.dot(w)) / denom;
}

std::optional<double> intersectPlane(const Ray& ray, const Eigen::Vector3d& point,
                                     const Eigen::Vector3d& normal) {
  const Eigen::Vector3d d = ray.direction.normalized();
  const double dn = d.dot(normal);
  if (std::abs(dn) < 1e-12 * normal.norm()) return std::nullopt;
  const double t = (point - ray.origin).dot(normal) / dn;
  if (t < 0.0) return std::nullopt;
  return t;
}

std::optional<double> intersectTriangle(const Ray& ray, const Eigen::Vector3d& a,
                                        const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d d = ray.direction.normalized();
  const Eigen::Vector3d e1 = b - a, e2 = c - a;
  const Eigen::Vector3d p = d.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-14) return std::nullopt;
  const double inv = 1.0 / det;
  const Eigen::Vector3d s = ray.origin - a;
  const double u = s.dot(p) * inv;
  if (u < 0.0 || u > 1.0) return std::nullopt;
  const Eigen::Vector3d q = s.cross(e1);
  const double v = d.dot(q) * inv;
  if (v < 0.0 || u + v > 1.0) return std::nullopt;
  const double t = e2.dot(q) * inv;
  if (t < 0.0) return std::nullopt;
  return t;
}

}  // namespace ffdkit::widgets
