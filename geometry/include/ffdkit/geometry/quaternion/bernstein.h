#pragma once

namespace ffdkit::geometry::quaternion {

/// B_{i,n}(t) = C(n,i) t^i (1-t)^(n-i); 0 for i outside 0..n. @see Miura 1998, sec. 3.3.
double bernstein(int degree, int i, double t);

/// Cumulative basis ~B_{i,n}(t) = sum_{j=i..n} B_{j,n}(t): ~B_0 = 1, ~B_i(0) = 0 and ~B_i(1) = 1
/// for i >= 1. @see Sphere-tangent report, sec. 3.2, eq. (13).
double cumulativeBernstein(int degree, int i, double t);

/// d/dt ~B_{i,n}(t) = n B_{i-1,n-1}(t) for i >= 1, and 0 for i = 0.
double cumulativeBernsteinDerivative(int degree, int i, double t);

}  // namespace ffdkit::geometry::quaternion
