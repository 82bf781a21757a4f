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
  return binomial(degree, i) * std::pow(t, i) * std::pow(1.0 - t, degree - i);
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
