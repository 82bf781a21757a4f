#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ffdkit::geometry::quaternion {

// Conventions shared by the three seeds (000, 003, 004): quaternion tuples are (w, x, y, z) and
// the product is Hamilton's, which is Eigen::Quaterniond's operator* (NB: Eigen's coeffs() are
// stored (x, y, z, w)). A 3-vector v is the pure quaternion (0, v).

/// The pure quaternion (0, v).
Eigen::Quaterniond pureQuaternion(const Eigen::Vector3d& v);

/// exp(v) = (cos|v|, sin|v| v/|v|): a rotation by 2|v| about v/|v| (Kim/Miura convention, NOT
/// Eigen::AngleAxisd(|v|, v/|v|)). exp(0) = identity; sin(x)/x uses its series below 1e-8.
/// @see Miura 1998, sec. 2.3, eq. (17); Sphere-tangent report, sec. 3.2, eq. (12).
Eigen::Quaterniond quaternionExp(const Eigen::Vector3d& v);

/// log(q) = theta n with theta = atan2(|vec q|, w) in [0, pi] and n = vec q / |vec q|; the
/// inverse of quaternionExp for |v| < pi. q need not be normalised (its norm is ignored).
/// No hemisphere flip: log(-q) != log(q) (Sphere-tangent report, sec. 3.2: -q is the opposite
/// tangent).
/// @throws QuaternionCurveError for q = 0 or q on the negative real axis (theta = pi, the axis
///   is undefined). @see Sphere-tangent report, sec. 3.2, eqs. (8)-(11).
Eigen::Vector3d quaternionLog(const Eigen::Quaterniond& q);

/// The fixed vector v rotated by the unit quaternion q: q v q^-1, evaluated as
/// v + 2w (u x v) + 2 u x (u x v) with q = (w, u). @see Miura 1998, sec. 2.2, eq. (15), eq. (20)
/// sec. 3.2.
Eigen::Vector3d rotateFixedVector(const Eigen::Quaterniond& q, const Eigen::Vector3d& v);

/// The angle between two non-zero vectors, atan2(|a x b|, a.b) in [0, pi] (acos loses ~1e-8).
double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

/// Great-circle interpolation between unit vectors a and b on S^2, t in [0, 1] (extrapolates
/// outside). Unlike Eigen::Quaterniond::slerp it never negates b, which would be wrong for
/// directions more than 90 degrees apart (Sphere-tangent report, sec. 4).
/// @throws QuaternionCurveError if a and b are antipodal (within 1e-12 rad): no unique arc.
Eigen::Vector3d slerpSphere(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double t);

/// The unit quaternion of the minimal rotation taking the unit vector `from` to the unit vector
/// `to`, in the exp convention: exp((theta/2) (from x to)/|from x to|). For antiparallel input the
/// axis is fallbackAxis made perpendicular to `from` (or any perpendicular if that fails).
/// @see Sakiyama et al. 2001, sec. 2.2.
Eigen::Quaterniond minimalRotation(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                   const Eigen::Vector3d& fallbackAxis = Eigen::Vector3d::UnitZ());

}  // namespace ffdkit::geometry::quaternion
