#pragma once

#include <optional>

#include <Eigen/Core>

namespace ffdkit::widgets {

/// A world-space ray from the camera through the mouse: origin + t * direction, t >= 0.
/// The GUI builds it from a mouse position; the model never sees pixels (STYLE 9).
struct Ray {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< world start point
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  ///< need not be unit; normalised on use

  /// The point at distance t along the (normalised) direction.
  Eigen::Vector3d at(double t) const { return origin + t * direction.normalized(); }
};

/// Ray parameter t (distance along the unit direction) and squared distance of the closest
/// approach between the ray and segment [a, b]; nullopt if the closest point is behind the ray.
struct RaySegmentHit {
  double t = 0.0;          ///< along the ray
  double s = 0.0;          ///< along the segment, in [0, 1]
  double distance = 0.0;   ///< between the two closest points
};
std::optional<RaySegmentHit> closestRaySegment(const Ray& ray, const Eigen::Vector3d& a,
                                               const Eigen::Vector3d& b);

/// Parameter s of the point of the line origin + s * axis (axis unit) closest to the ray's line;
/// nullopt when the two are parallel (no unique closest point).
std::optional<double> closestLineParameter(const Ray& ray, const Eigen::Vector3d& origin,
                                           const Eigen::Vector3d& axis);

/// Ray parameter t where the ray meets the plane through `point` with normal `normal`;
/// nullopt when parallel or behind the origin.
std::optional<double> intersectPlane(const Ray& ray, const Eigen::Vector3d& point,
                                     const Eigen::Vector3d& normal);

/// Ray parameter t of the first hit of triangle (a, b, c) (Möller & Trumbore 1997).
std::optional<double> intersectTriangle(const Ray& ray, const Eigen::Vector3d& a,
                                        const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace ffdkit::widgets
