#include "ffdkit/ffd/bernstein_basis.h"

#include <stdexcept>
#include <string>

namespace ffdkit::ffd {

Eigen::VectorXd bernsteinBasis(int degree, double t) {
  if (degree < 0) {
    throw std::invalid_argument("bernsteinBasis: degree must be >= 0, got " + std::to_string(degree));
  }
  // de Casteljau on the unit vectors: b holds the degree-r basis after round r.
  Eigen::VectorXd b = Eigen::VectorXd::Zero(degree + 1);
  b[0] = 1.0;
  const double s = 1.0 - t;
  for (int r = 1; r <= degree; ++r) {
    for (int i = r; i >= 1; --i) b[i] = s * b[i] + t * b[i - 1];
    b[0] *= s;
  }
  return b;
}

}  // namespace ffdkit::ffd
