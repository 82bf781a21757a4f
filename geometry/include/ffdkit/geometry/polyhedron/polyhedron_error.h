#pragma once

#include <stdexcept>
#include <string>

namespace ffdkit::geometry::polyhedron {

/// Raised for polyhedra, tensions or options that the Kuriyama 1996, ch. 4 construction cannot
/// handle (non-manifold edges, degenerate faces, valence-2 vertices, collapsed tangent frames,
/// ...). The message says what was expected, what came and where (vertex, edge or face index).
class PolyhedronError : public std::runtime_error {
 public:
  /// An error with `message`.
  explicit PolyhedronError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace ffdkit::geometry::polyhedron
