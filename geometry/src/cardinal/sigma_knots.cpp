#include "ffdkit/geometry/cardinal/sigma_knots.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "ffdkit/geometry/cardinal/cardinal_error.h"

#include "floor_mod.h"

namespace ffdkit::geometry::cardinal {
using detail::floorMod;

SigmaKnots::SigmaKnots(const Eigen::VectorXd& knots, const Eigen::VectorXd& beta2,
                       const SigmaKnotsOptions& options)
    : t_(knots), options_(options) {
  n_ = static_cast<int>(knots.size()) - 1;
  const int minN = options.closed ? 3 : 1;
  if (n_ < minN) {
    throw CardinalSplineError(std::string("SigmaKnots: ") + (options.closed ? "closed" : "open") +
                              " knots need >= " + std::to_string(minN + 1) + " values, got " +
                              std::to_string(knots.size()));
  }
  if (!knots.allFinite()) throw CardinalSplineError("SigmaKnots: knots must be finite");
  const double range = t_[n_] - t_[0];
  for (int i = 0; i < n_; ++i) {
    if (!(t_[i + 1] - t_[i] > 1e-12 * std::abs(range)) || !(range > 0.0)) {
      throw CardinalSplineError("SigmaKnots: knots must increase strictly, got t[" +
                                std::to_string(i) + "] = " + std::to_string(t_[i]) + ", t[" +
                                std::to_string(i + 1) + "] = " + std::to_string(t_[i + 1]));
    }
  }
  const int betaCount = options.closed ? n_ : n_ + 1;
  if (beta2.size() == 0) {
    beta2_ = Eigen::VectorXd::Zero(betaCount);
  } else if (beta2.size() != betaCount) {
    throw CardinalSplineError("SigmaKnots: expected " + std::to_string(betaCount) +
                              " beta2 values (one per " + (options.closed ? "distinct " : "") +
                              "knot), got " + std::to_string(beta2.size()));
  } else {
    beta2_ = beta2;
  }
  for (int i = 0; i < betaCount; ++i) {
    // Negative tension can make D_i vanish (Kuriyama 1996, sec. 3.2.2): rejected.
    if (!(beta2_[i] >= 0.0) || !std::isfinite(beta2_[i])) {
      throw CardinalSplineError("SigmaKnots: beta2[" + std::to_string(i) +
                                "] must be finite and >= 0, got " + std::to_string(beta2_[i]));
    }
  }
  for (const auto& phantom : {options.phantomBefore, options.phantomAfter}) {
    if (phantom && !(*phantom > 0.0 && std::isfinite(*phantom))) {
      throw CardinalSplineError("SigmaKnots: phantom interval widths must be > 0, got " +
                                std::to_string(*phantom));
    }
  }
}

SigmaKnots SigmaKnots::uniform(int n, bool closed) {
  SigmaKnotsOptions options;
  options.closed = closed;
  return SigmaKnots(Eigen::VectorXd::LinSpaced(std::max(n, 0) + 1, 0.0, std::max(n, 0)), {},
                    options);
}

double SigmaKnots::knot(int i) const {
  if (!closed()) {
    if (i < 0) return t_[0] - (-i) * delta(-1);
    if (i > n_) return t_[n_] + (i - n_) * delta(n_);
    return t_[i];
  }
  const double period = t_[n_] - t_[0];
  const int r = floorMod(i, n_);
  const int turns = (i - r) / n_;
  return t_[r] + turns * period;
}

double SigmaKnots::delta(int i) const {
  if (closed()) {
    const int r = floorMod(i, n_);
    return t_[r + 1] - t_[r];
  }
  if (i < 0) return options_.phantomBefore.value_or(t_[1] - t_[0]);
  if (i >= n_) return options_.phantomAfter.value_or(t_[n_] - t_[n_ - 1]);
  return t_[i + 1] - t_[i];
}

double SigmaKnots::beta2(int i) const {
  if (closed()) return beta2_[floorMod(i, n_)];
  return beta2_[std::clamp(i, 0, n_)];
}

double SigmaKnots::D(int i) const {
  return 2.0 / delta(i - 1) + 2.0 / delta(i) + beta2(i) / 3.0;
}

double SigmaKnots::C0(int i) const {
  const double dm = delta(i - 1), d = delta(i);
  return (dm / (d * d) + 1.0 / dm + 2.0 / d + beta2(i) / 3.0) / D(i);
}

double SigmaKnots::C1(int i) const {
  const double dm = delta(i - 1), d = delta(i);
  return (d / (dm * dm) + 1.0 / d + 2.0 / dm + beta2(i) / 3.0) / D(i);
}

double SigmaKnots::Chat0(int i) const {
  const double d = delta(i);
  return -delta(i - 1) / (d * d * D(i));
}

double SigmaKnots::Chat1(int i) const { return 1.0 / (delta(i) * D(i)); }

double SigmaKnots::Chat3(int i) const { return 1.0 / (delta(i) * D(i + 1)); }

double SigmaKnots::Chat4(int i) const {
  const double d = delta(i);
  return -delta(i + 1) / (d * d * D(i + 1));
}

int SigmaKnots::locate(double x, double& s) const {
  if (closed()) {
    const double period = t_[n_] - t_[0];
    x = t_[0] + (x - t_[0]) - period * std::floor((x - t_[0]) / period);
    if (x >= t_[n_]) x = t_[0];
  } else {
    x = std::clamp(x, t_[0], t_[n_]);
  }
  const double* begin = t_.data();
  const double* found = std::upper_bound(begin, begin + n_ + 1, x);
  int i = static_cast<int>(found - begin) - 1;
  i = std::clamp(i, 0, n_ - 1);
  s = (x - t_[i]) / (t_[i + 1] - t_[i]);
  return i;
}

}  // namespace ffdkit::geometry::cardinal
