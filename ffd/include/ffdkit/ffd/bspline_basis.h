#pragma once

#include <Eigen/Core>

namespace ffdkit::ffd {

/// Clamped uniform knot vector for `count` control points of degree `degree`:
/// degree+1 zeros, count-degree-1 equally spaced interior knots, degree+1 ones.
/// Length count + degree + 1; the parameter domain is [0, 1].
/// @throws LatticeError unless 1 <= degree <= count - 1.
Eigen::VectorXd clampedUniformKnots(int count, int degree);

/// Periodic (unclamped) uniform knot vector for a closed axis with `count` distinct control
/// points of degree `degree`: t_i = (i - degree) / count, i = 0 .. count + 2*degree.
/// Basis function i acts on control point (i mod count); the domain is [t_degree, t_(degree+count)] = [0, 1].
/// @throws LatticeError unless 1 <= degree <= count - 1.
Eigen::VectorXd periodicUniformKnots(int count, int degree);

/// The degree+1 B-spline basis functions of degree `degree` that are non-zero on the knot span
/// [knots[span], knots[span+1]), evaluated at t: values[r] = N_(span-degree+r, degree)(t).
/// Cox-de Boor recursion (Piegl & Tiller, The NURBS Book, A2.2). For t outside the span the
/// span's polynomial piece is evaluated (extrapolation). knots[span] < knots[span+1] required.
/// `values` must hold degree+1 doubles; `derivatives` (may be null) receives dN/dt (A2.3).
void bsplineBasisOnSpan(const double* knots, int span, int degree, double t, double* values,
                        double* derivatives = nullptr);

/// Same as bsplineBasisOnSpan, returned by value (degree+1 entries). Convenience for tests.
Eigen::VectorXd bsplineBasis(const Eigen::Ref<const Eigen::VectorXd>& knots, int span, int degree,
                             double t);

/// Greville abscissae g_i = (t_(i+1) + ... + t_(i+degree)) / degree, i = 0..count-1: control points
/// placed at g_i make the spline reproduce the identity map (linear precision), which is what makes
/// a box lattice's rest map affine (Kuriyama 1996, sec. 6.3.2).
Eigen::VectorXd grevilleAbscissae(const Eigen::Ref<const Eigen::VectorXd>& knots, int count, int degree);

}  // namespace ffdkit::ffd
