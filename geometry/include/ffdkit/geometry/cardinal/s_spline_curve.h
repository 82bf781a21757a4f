#pragma once

#include <Eigen/Core>

#include "ffdkit/geometry/cardinal/s_spline_basis.h"

namespace ffdkit::geometry::cardinal {

/// How an S-spline supplies the data beyond its ends (Kuriyama 1996, sec. 3.2.4).
enum class SSplineEnd {
  Open,     ///< P_i = P_0 for i < 0, P_i = P_s for i > s
  Closed,   ///< P_i = P_{i mod s}; the input holds s distinct points (P_s := P_0)
  Tangent,  ///< P_i = P_{-i} - dP_0 (i < 0), P_i = P_{2s-i} + dP_s (i > s)
};

/// Options of an S-spline curve.
struct SSplineCurveOptions {
  double beta2 = 0.0;  ///< tension (>= 0); 0 gives the uniform cubic B-spline version
  int halfWidth = 4;   ///< truncation half-width w (the thesis's n); support is 2w spans
  SSplineEnd end = SSplineEnd::Open;  ///< how the ends are treated
  Eigen::Vector3d startTangent = Eigen::Vector3d::Zero();  ///< dP_0 for SSplineEnd::Tangent
  Eigen::Vector3d endTangent = Eigen::Vector3d::Zero();    ///< dP_s for SSplineEnd::Tangent
  /// Divide the tangents by lambda_w so that they set the end derivative up to the
  /// truncation residue (Kuriyama 1996, sec. 3.2.4). false is the thesis behaviour.
  bool scaleTangent = false;
  int degree = 3;      ///< odd B-spline degree; 5..9 need beta2 = 0 (Kuriyama 1996, sec. 3.2.2)
  /// false: an unclipped variant, not in the thesis (exactly C2 / G2-beta, approximate
  /// interpolation).
  bool clipped = true;
};

/// S-spline curve Q(x) = sum_i P_i S_i(x), x in [0, s] (open) or [0, s) periodic (closed);
/// data point P_k sits at x = k. Interpolates exactly: Q(k) = P_k.
/// @see Kuriyama 1996, sec. 3.2.4, eq. (3.11).
class SSplineCurve {
 public:
  /// points: #P x 3. Open/tangent need >= 2 points (s >= 1); closed needs >= 3 distinct points.
  /// @throws CardinalSplineError on too few points or invalid options.
  SSplineCurve(const Eigen::MatrixX3d& points, const SSplineCurveOptions& options = {});

  /// Parameter range end s (open: #P - 1; closed: #P).
  double parameterEnd() const { return static_cast<double>(span_); }
  /// True for a closed (periodic) curve.
  bool closed() const { return options_.end == SSplineEnd::Closed; }
  /// The basis the curve uses.
  const SSplineBasis& basis() const { return basis_; }
  /// The data points, #P x 3.
  const Eigen::MatrixX3d& points() const { return points_; }

  /// Extended data P_i for any integer i (end rule applied).
  Eigen::Vector3d extendedPoint(int i) const;

  /// Q^(deriv)(x) in knot-index units. Closed curves wrap x; open curves evaluate the
  /// extension outside [0, s]. deriv in 0..3; see SSplineBasis::evaluate for `side`.
  Eigen::Vector3d evaluate(double x, int deriv = 0, Limit side = Limit::Value) const;

 private:
  Eigen::MatrixX3d points_;
  SSplineCurveOptions options_;
  SSplineBasis basis_;
  int span_ = 0;
  Eigen::Vector3d startTangent_, endTangent_;
};

}  // namespace ffdkit::geometry::cardinal
