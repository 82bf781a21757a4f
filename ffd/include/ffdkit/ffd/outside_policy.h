#pragma once

namespace ffdkit::ffd {

/// What happens to an object point outside the rest lattice (Kuriyama 1996, sec. 6.3.2).
/// The boundary test is epsilon-inclusive: a point on a face of the lattice is inside.
struct OutsidePolicy {
  /// The kinds of outside behaviour.
  enum class Kind {
    Identity,     ///< default: outside points are left where they are.
    ClampEdge,    ///< parameters clamped into the box; the point keeps its offset from the clamped
                  ///< rest surface point (Blender's lattice behaviour).
    Extrapolate,  ///< evaluate the end polynomial pieces beyond the box (meant for Bernstein).
    Falloff       ///< ClampEdge at the boundary blended to Identity at distance `distance`.
  };
  Kind kind = Kind::Identity;  ///< the behaviour.
  double distance = 0.0;  ///< Falloff only: > 0, lattice-local length units.

  /// Outside points left where they are (the default).
  static OutsidePolicy identity() { return {Kind::Identity, 0.0}; }
  /// Outside points follow the nearest boundary point of the lattice.
  static OutsidePolicy clampEdge() { return {Kind::ClampEdge, 0.0}; }
  /// Outside points follow the end polynomial pieces beyond the box.
  static OutsidePolicy extrapolate() { return {Kind::Extrapolate, 0.0}; }
  /// @param distance blend length in lattice-local units, must be > 0 (checked by Lattice).
  static OutsidePolicy falloff(double distance) { return {Kind::Falloff, distance}; }

  /// Equal when kind and distance are.
  bool operator==(const OutsidePolicy&) const = default;
};

}  // namespace ffdkit::ffd
