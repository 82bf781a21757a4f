#pragma once

#include <stdexcept>
#include <string>

namespace ffdkit::geometry::cardinal {

/// Invalid input to a cardinal-spline routine (wrong sizes, non-increasing knots, negative
/// tension, ...). The message says what was expected, what came and where.
class CardinalSplineError : public std::invalid_argument {
 public:
  /// An error with the message `what`.
  explicit CardinalSplineError(const std::string& what) : std::invalid_argument(what) {}
};

}  // namespace ffdkit::geometry::cardinal
