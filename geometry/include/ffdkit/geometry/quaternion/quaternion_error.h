#pragma once

#include <stdexcept>
#include <string>

namespace ffdkit::geometry::quaternion {

/// Invalid input to a quaternion-curve model, solver or generator. The message says what was
/// expected, what came, and where (function / parameter).
class QuaternionCurveError : public std::invalid_argument {
 public:
  /// An error with `message`.
  explicit QuaternionCurveError(const std::string& message) : std::invalid_argument(message) {}
};

}  // namespace ffdkit::geometry::quaternion
