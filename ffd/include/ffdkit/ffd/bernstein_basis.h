#pragma once

#include <Eigen/Core>

namespace ffdkit::ffd {

/// Values of the n+1 Bernstein polynomials of degree n at t:
/// B_i(t) = C(n,i) t^i (1-t)^(n-i), i = 0..n (Sederberg & Parry 1986, eq. 1;
/// Kuriyama 1996, eq. (6.1) uses them per lattice axis).
/// Evaluated with de Casteljau's triangle, stable for t outside [0, 1] too (extrapolation).
/// @throws std::invalid_argument if degree < 0.
Eigen::VectorXd bernsteinBasis(int degree, double t);

}  // namespace ffdkit::ffd
