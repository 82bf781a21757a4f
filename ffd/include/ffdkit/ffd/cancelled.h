#pragma once

#include <stdexcept>
#include <string>

namespace ffdkit::ffd {

/// A long computation (embed(), Pipeline::update() / reembedAll(), scenes::SceneDeformer)
/// stopped because its progress callback returned false. Not an input error: nothing is wrong
/// with the lattice or the points, and running the same call again without cancelling gives
/// the result a never-cancelled run would have given. What each caller keeps after a cancel is
/// documented where the callback is taken (EmbedOptions::progress, Pipeline::update()).
class Cancelled : public std::runtime_error {
 public:
  /// A cancellation with `message` (what was stopped, and what was kept).
  explicit Cancelled(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace ffdkit::ffd
