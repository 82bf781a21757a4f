#pragma once

#include <stdexcept>
#include <string>

namespace ffdkit::geometry::g3 {

/// Invalid input to the G3 curve topic (points, span lengths, conditions, options). The
/// message says what was expected, what came and where.
class G3InputError : public std::invalid_argument {
 public:
  /// An error with the message `what` (prefixed "g3: ").
  explicit G3InputError(const std::string& what) : std::invalid_argument("g3: " + what) {}
};

/// A curve was requested from a solve that did not converge (e.g. the infeasible Fig. 2(d)
/// set-up). Thrown by the generator only; the solver itself reports failures in its result.
class G3SolveError : public std::runtime_error {
 public:
  /// An error with the message `what` (prefixed "g3: ").
  explicit G3SolveError(const std::string& what) : std::runtime_error("g3: " + what) {}
};

}  // namespace ffdkit::geometry::g3
