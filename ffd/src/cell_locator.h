// Internal to ffd/: the lattice cell of a parameter, fast.
#pragma once

#include <algorithm>
#include <vector>

#include "ffdkit/ffd/axis_basis.h"

namespace ffdkit::ffd::detail {

// AxisSpline::cellOf without the binary search: a guess from uniform breaks, corrected against
// the true breaks, so the cell is the same as cellOf's for every t (periodic axes: for every
// wrapped t).
class CellLocator {
 public:
  explicit CellLocator(const AxisSpline& axis) : cells_(axis.cellCount()) {
    for (int c = 0; c < cells_; ++c) breaks_.push_back(axis.cellMin(c));
    breaks_.push_back(axis.cellMax(cells_ - 1));
    lo_ = breaks_.front();
    scale_ = cells_ / (breaks_.back() - breaks_.front());
  }
  int operator()(double t) const {
    if (cells_ == 1 || !(t > breaks_[1])) return 0;  // also catches NaN, as cellOf does
    if (t >= breaks_[cells_ - 1]) return cells_ - 1;
    int c = std::clamp(static_cast<int>((t - lo_) * scale_), 1, cells_ - 2);
    while (t < breaks_[c]) --c;
    while (t >= breaks_[c + 1]) ++c;
    return c;
  }

 private:
  int cells_;
  std::vector<double> breaks_;
  double lo_ = 0.0, scale_ = 1.0;
};

}  // namespace ffdkit::ffd::detail
