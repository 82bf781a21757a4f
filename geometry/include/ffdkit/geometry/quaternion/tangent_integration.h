#pragma once

#include <functional>

#include <Eigen/Core>

namespace ffdkit::geometry::quaternion {

/// A unit tangent (or any 3-vector integrand) as a function of the curve's normalised
/// parameter t in [0, 1].
using TangentFunction = std::function<Eigen::Vector3d(double)>;

/// Composite Simpson integral of f over [a, b] with `intervals` equal subintervals
/// (intervals + 1 nodes, weights h/3 (1, 4, 2, ..., 4, 1)). Miura 1998 integrates its QI tangents
/// this way with 100 subintervals. @see Miura 1998, sec. 5.1.
/// @throws QuaternionCurveError if intervals is not a positive even number.
Eigen::Vector3d integrateSimpson(const TangentFunction& f, double a, double b, int intervals);

/// Cumulative composite Gauss-Legendre integrals of f from 0 to each of the sorted parameters
/// `params` (values in [0, 1]). The panels are the union of the parameters and a uniform grid of
/// `minPanels` panels, each integrated with `order` Gauss-Legendre points, so the nodes depend only
/// on `params` (smooth objective for optimisers).
/// @return #params x 3, row k = int_0^{params[k]} f(t) dt.
/// @throws QuaternionCurveError if params are not sorted inside [0, 1], order < 1 or minPanels < 1.
Eigen::MatrixX3d cumulativeGaussLegendre(const TangentFunction& f, const Eigen::VectorXd& params,
                                         int order, int minPanels);

/// Integral of f over [0, 1] with `panels` equal panels of `order` Gauss-Legendre points.
Eigen::Vector3d integrateGaussLegendrePanels(const TangentFunction& f, int order, int panels);

}  // namespace ffdkit::geometry::quaternion
