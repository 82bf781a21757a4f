#pragma once
// Internal: an angle difference brought into [-pi, pi), for unwrapping a dragged rotation.

#include <cmath>
#include <numbers>

namespace ffdkit::app::detail {

inline double wrapAngle(double a) {
  constexpr double twoPi = 2.0 * std::numbers::pi;
  a = std::fmod(a + std::numbers::pi, twoPi);
  if (a < 0.0) a += twoPi;
  return a - std::numbers::pi;
}

}  // namespace ffdkit::app::detail
