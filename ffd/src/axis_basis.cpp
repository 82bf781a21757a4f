#include "ffdkit/ffd/axis_basis.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "ffdkit/ffd/bspline_basis.h"
#include "ffdkit/ffd/lattice_error.h"

namespace ffdkit::ffd {

AxisSpline::AxisSpline(const AxisBasis& basis, int count, const char* axisName) : basis_(basis), count_(count) {
  const std::string where = std::string(axisName) + ": ";
  if (count < 2) {
    throw LatticeError(where + "needs >= 2 control points, got " + std::to_string(count));
  }
  constexpr int kMaxDegree = 32;
  Eigen::VectorXd knots;
  switch (basis.kind) {
    case AxisBasis::Kind::Bernstein:
      degree_ = count - 1;
      if (degree_ > kMaxDegree) {
        throw LatticeError(where + "Bernstein degree must be <= " + std::to_string(kMaxDegree) + ", got " +
                           std::to_string(degree_));
      }
      knots.resize(2 * count);
      knots.head(count).setZero();
      knots.tail(count).setOnes();
      break;
    case AxisBasis::Kind::BSpline:
      degree_ = basis.degree;
      if (degree_ < 1 || degree_ > count - 1 || degree_ > kMaxDegree) {
        throw LatticeError(where + "B-spline degree must be in [1, " + std::to_string(std::min(count - 1, kMaxDegree)) +
                           "] for " + std::to_string(count) + " control points, got " + std::to_string(degree_));
      }
      if (basis.knots.size() == 0) {
        knots = clampedUniformKnots(count, degree_);
      } else {
        knots = basis.knots;
        if (knots.size() != count + degree_ + 1) {
          throw LatticeError(where + "knot vector needs count+degree+1 = " + std::to_string(count + degree_ + 1) +
                             " values, got " + std::to_string(knots.size()));
        }
        for (Eigen::Index i = 0; i < knots.size(); ++i) {
          if (!std::isfinite(knots[i])) {
            throw LatticeError(where + "knot " + std::to_string(i) + " is not finite");
          }
          if (i > 0 && knots[i] < knots[i - 1]) {
            throw LatticeError(where + "knots must be non-decreasing, but knot " + std::to_string(i) + " = " +
                               std::to_string(knots[i]) + " < knot " + std::to_string(i - 1) + " = " +
                               std::to_string(knots[i - 1]));
          }
          // A knot repeated more than degree+1 times would make a basis function vanish identically.
          if (i >= degree_ + 1 && knots[i] == knots[i - degree_ - 1]) {
            throw LatticeError(where + "knot " + std::to_string(knots[i]) + " is repeated more than degree+1 = " +
                               std::to_string(degree_ + 1) + " times");
          }
        }
        if (!(knots[degree_] < knots[count])) {
          throw LatticeError(where + "empty parameter domain [knots[degree], knots[count]] = [" +
                             std::to_string(knots[degree_]) + ", " + std::to_string(knots[count]) + "]");
        }
      }
      break;
    case AxisBasis::Kind::PeriodicBSpline:
      degree_ = basis.degree;
      if (degree_ < 1 || degree_ > count - 1 || degree_ > kMaxDegree) {
        throw LatticeError(where + "periodic B-spline degree must be in [1, " +
                           std::to_string(std::min(count - 1, kMaxDegree)) + "] for " + std::to_string(count) +
                           " control points, got " + std::to_string(degree_));
      }
      if (basis.knots.size() != 0) {
        throw LatticeError(where + "periodic axes use uniform knots; explicit knots are not supported");
      }
      periodic_ = true;
      knots = periodicUniformKnots(count, degree_);
      break;
  }
  knots_.assign(knots.data(), knots.data() + knots.size());
  const int lastSpan = periodic_ ? degree_ + count - 1 : count - 1;
  lo_ = knots_[degree_];
  hi_ = knots_[lastSpan + 1];
  for (int s = degree_; s <= lastSpan; ++s) {
    if (knots_[s] < knots_[s + 1]) {
      cellSpan_.push_back(s);
      breaks_.push_back(knots_[s]);
    }
  }
  breaks_.push_back(hi_);
  for (const int span : cellSpan_) {
    for (int j = 1; j <= degree_; ++j)
      for (int r = 0; r < j; ++r) inverses_.push_back(1.0 / (knots_[span + r + 1] - knots_[span + 1 - j + r]));
  }
  greville_ = grevilleAbscissae(knots, count, degree_);
  if (periodic_) {
    for (int i = 0; i < count; ++i) greville_[i] = wrap(greville_[i]);
  }
}

}  // namespace ffdkit::ffd
