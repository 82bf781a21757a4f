#include "ffdkit/geometry/quaternion/bernstein.h"

#include <cmath>

namespace ffdkit::geometry::quaternion {

namespace {
double binomial(int n, int k) {
  double r = 1.0;
  for (int j = 1; j <= k; ++j) {
    r = r * (n - k + j) / j;
  }
  return r;
}
}  // namespace

double bernstein(int degree, int i, double t) {
  if (i < 0 || i > degree) {
    return 0.0;
  }
  // Repeated products instead of std::pow: this sits in the innermost loop of every fit.
  double v = binomial(degree, i);
  for (int j = 0; j < i; ++j) v *= t;
  const double s = 1.0 - t;
  for (int j = i; j < degree; ++j) v *= s;
  return v;
}

double cumulativeBernstein(int degree, int i, double t) {
  if (i <= 0) {
    return 1.0;
  }
  double sum = 0.0;
  for (int j = i; j <= degree; ++j) {
    sum += bernstein(degree, j, t);
  }
  return sum;
}

double cumulativeBernsteinDerivative(int degree, int i, double t) {
  if (i <= 0 || i > degree) {
    return 0.0;
  }
  return degree * bernstein(degree - 1, i - 1, t);
}

}  // namespace ffdkit::geometry::quaternion
