#pragma once

#include <stdexcept>
#include <string>

namespace ffdkit::cad {

/// A CAD file that cannot be read or written, a shape OpenCASCADE rejects, or a deformation the
/// CAD module cannot make exactly. The message names the file (or part and face) and what failed.
class CadError : public std::runtime_error {
 public:
  /// An error whose what() is `message`.
  explicit CadError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace ffdkit::cad
