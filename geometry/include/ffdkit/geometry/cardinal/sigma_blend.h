#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "ffdkit/geometry/cardinal/sigma_surface.h"

namespace ffdkit::geometry::cardinal {

/// Options of a blend between two sigma-spline surfaces.
struct BlendOptions {
  /// Width of the blend's first v-interval [v_n, v_{n+1}]; unset: surface 1's last v-interval.
  std::optional<double> gapBefore;
  /// Width of [v_{n+1}, v_{n+2}]; unset: surface 2's first v-interval.
  std::optional<double> gapAfter;
  /// beta2 at v_n, v_{n+1}, v_{n+2} (>= 0).
  std::array<double, 3> junctionBeta2 = {0.0, 0.0, 0.0};
};

/// The blend and the composite surface.
struct BlendResult {
  /// The blend surface alone, on v in [v_n, v_{n+2}] (its open v-knots carry the neighbouring
  /// widths as phantoms, so it is exactly the composite restricted to the blend region).
  SigmaSurface blend;
  /// Surface 1, blend and surface 2 as one sigma-surface on the concatenated v knots; equal
  /// to surface 1 on [v_0, v_n] and to surface 2 (shifted in v) on [v_{n+2}, ...].
  SigmaSurface composite;
  /// v offset added to surface 2's v parameters in the composite.
  double surface2VOffset = 0.0;
  /// Weights of (P_n, P_{n+2}, Pv_{n-1}, Pv_n, Pv_{n+1}, Pv_{n+2}) giving the middle row
  /// P_{n+1} (eq. 3.39); they sum to 1.
  std::array<double, 6> middleWeights{};
  /// Non-fatal findings, e.g. different beta2 at a shared u-knot (the blend is then G1 only).
  std::vector<std::string> warnings;
};

/// Blends surface 1's v-end to surface 2's v-start with two sigma intervals whose middle knot
/// row minimises int ||q''||^2 per column (eq. 3.36-3.39). Both surfaces are first refined to
/// the union of their u knots (Kuriyama 1996, sec. 3.3.6). The originals are reproduced exactly;
/// with all beta2 = 0 the composite is C2 across v_n and v_{n+2} (G1 otherwise, sec. 3.3.7).
/// @see Kuriyama 1996, sec. 3.3.7.
/// @throws CardinalSplineError if a surface is closed in v, the u closedness or u ranges differ.
BlendResult blendSurfaces(const SigmaSurface& first, const SigmaSurface& second,
                          const BlendOptions& options = {});

}  // namespace ffdkit::geometry::cardinal
