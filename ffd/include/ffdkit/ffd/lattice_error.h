#pragma once

#include <stdexcept>
#include <string>

namespace ffdkit::ffd {

/// Bad input to the FFD engine: a lattice with fewer than two points on an axis, a degree out
/// of range, bad knots, non-finite coordinates, a zero-volume rest lattice, a stale embedding.
/// Messages say what was expected, what came, and where, e.g.
/// `lattice needs >= 2 points per axis, got (1, 4, 4)`.
/// Checked in release builds too.
class LatticeError : public std::invalid_argument {
 public:
  /// An error with `message`, which says what was expected and what came.
  explicit LatticeError(const std::string& message) : std::invalid_argument(message) {}
};

}  // namespace ffdkit::ffd
