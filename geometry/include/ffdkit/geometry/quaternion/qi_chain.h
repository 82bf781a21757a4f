#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ffdkit/geometry/quaternion/arc_length_curve.h"
#include "ffdkit/geometry/quaternion/cumulative_bezier_quaternion.h"

namespace ffdkit::geometry::quaternion {

/// Quadrature for QI chains: composite Gauss-Legendre with `order` points on at least
/// `minPanels` equal panels per segment (GL-8, nsub = 8: our choice; the paper does not say how it
/// integrates).
struct QiQuadrature {
  int order = 8;      ///< Gauss-Legendre points per panel
  int minPanels = 8;  ///< uniform panels per segment (data parameters add breakpoints)
};

/// One Bezier-type QI segment of Sakiyama et al. 2001: start point P, start orientation q_0,
/// angular-derivative vectors w_1..w_k (world frame), length l; local parameter u = s / l in [0, 1]
/// and tangent t(u) = q(u) v0 q(u)^-1 with the cumulative quaternion q of
/// CumulativeBezierQuaternion.
/// @see Sakiyama et al. 2001, sec. 2.2, eq. (4).
class QiChainSegment {
 public:
  /// @throws QuaternionCurveError if length <= 0 or omegas is empty.
  QiChainSegment(const Eigen::Vector3d& start, const Eigen::Quaterniond& q0, std::vector<Eigen::Vector3d> omegas,
                 double length, ProductForm form = ProductForm::Global,
                 const Eigen::Vector3d& v0 = Eigen::Vector3d::UnitX(), QiQuadrature quadrature = {});

  /// Start point of the segment.
  const Eigen::Vector3d& start() const { return start_; }
  /// Arc length l of the segment.
  double length() const { return length_; }
  /// The segment's quaternion curve q(u).
  const CumulativeBezierQuaternion& rotation() const { return rotation_; }
  /// Its angular-derivative vectors.
  const std::vector<Eigen::Vector3d>& omegas() const { return rotation_.omegas(); }
  /// Its degree.
  int degree() const { return rotation_.degree(); }
  /// The vector v0 that q(u) rotates into the tangent.
  const Eigen::Vector3d& fixedVector() const { return v0_; }

  /// q(u), renormalised.
  Eigen::Quaterniond orientation(double u) const;
  /// Unit tangent t(u) = q(u) v0 q(u)^-1.
  Eigen::Vector3d tangent(double u) const;
  /// World angular velocity Omega(u) = 2 vec(q' q^-1) (u-rate): dt/du = Omega x t.
  Eigen::Vector3d angularVelocity(double u) const;
  /// dt/du.
  Eigen::Vector3d tangentDerivative(double u) const;
  /// |Omega x t| / l.
  double curvature(double u) const;
  /// Signed curvature ((t x dt/du) . e_z) / l for curves in a plane z = const.
  double signedPlanarCurvature(double u) const;
  /// det(t, t_u, t_uu) / (l |t_u|^2) with t_uu by a 5-point difference of the analytic t_u.
  double torsion(double u) const;
  /// P + l int_0^u t.
  Eigen::Vector3d point(double u) const;
  /// Positions at sorted local parameters in [0, 1] (one cumulative sweep): #u x 3.
  Eigen::MatrixX3d points(const Eigen::VectorXd& sortedU) const;
  /// P + l int_0^1 t and q(1): where the next segment starts (Sakiyama et al. 2001, eqs. (6), (8)).
  Eigen::Vector3d endPoint() const;
  /// q(1): the orientation the next segment starts with.
  Eigen::Quaterniond endOrientation() const;

 private:
  Eigen::Vector3d start_;
  CumulativeBezierQuaternion rotation_;
  double length_;
  Eigen::Vector3d v0_;
  QiQuadrature quadrature_;
};

/// A G1 chain of QiChainSegment: segment i+1 starts at the end point and end orientation of
/// segment i (Sakiyama et al. 2001, sec. 2.2, eqs. (5)-(8)). G2 is NOT enforced (sec. 2.2).
class QiChain : public ArcLengthCurve {
 public:
  /// Empty chain starting at `start` with orientation q00.
  QiChain(const Eigen::Vector3d& start, const Eigen::Quaterniond& q00, ProductForm form = ProductForm::Global,
          const Eigen::Vector3d& v0 = Eigen::Vector3d::UnitX(), QiQuadrature quadrature = {});

  /// Appends a segment with the given angular-derivative vectors and length.
  /// @throws QuaternionCurveError if length <= 0 or omegas is empty.
  void appendSegment(std::vector<Eigen::Vector3d> omegas, double length);

  /// Number of segments.
  int segmentCount() const { return static_cast<int>(segments_.size()); }
  /// Segment i.
  const QiChainSegment& segment(int i) const { return segments_[i]; }
  /// Every segment, in order.
  const std::vector<QiChainSegment>& segments() const { return segments_; }
  /// Global or local product form.
  ProductForm form() const { return form_; }

  /// Position at the global parameter u in [0, M] (segment floor(u), Sakiyama et al. 2001,
  /// eq. (5)).
  Eigen::Vector3d pointAtGlobal(double u) const;
  /// Arc length at the global parameter u.
  double arcLengthAtGlobal(double u) const;
  /// (segment, local u) of an arc length (clamped).
  std::pair<int, double> locate(double s) const;

  double length() const override;
  Eigen::Vector3d position(double s) const override;
  Eigen::Vector3d tangent(double s) const override;
  double curvature(double s) const override;
  double torsion(double s) const override;
  Eigen::Vector3d curvatureVector(double s) const override;
  Eigen::MatrixX3d samplePositions(int count) const override;

 private:
  Eigen::Vector3d start_;
  Eigen::Quaterniond q00_;
  ProductForm form_;
  Eigen::Vector3d v0_;
  QiQuadrature quadrature_;
  std::vector<QiChainSegment> segments_;
};

}  // namespace ffdkit::geometry::quaternion
