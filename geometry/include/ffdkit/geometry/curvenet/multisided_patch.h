#pragma once

#include <Eigen/Core>

#include "ffdkit/geometry/curvenet/curve_network.h"
#include "ffdkit/geometry/curvenet/jet.h"
#include "ffdkit/geometry/curvenet/ngon_domain.h"

namespace ffdkit::geometry::curvenet {

/// Options of the N-sided patch.
struct PatchOptions {
  /// m of B_i^m. Default m = n + 1 = 3 for C^2 cubic networks: G^3 on regular edges, G^2 with
  /// the special rules (Kuriyama 1996, sec. 5.2.3 (ii)-(iii)). m = 1 loses G^2 (negative control
  /// P7).
  int blendingExponent = 3;
};

/// The sweep of a run (Kuriyama 1996, sec. 5.2.1, eq. (5.2)), shared by the faces on both
/// sides: F(u~, v) = g-(u~) C^-(v) + g+(u~) C^+(v) + K(tStart + Delta u~), with C^-+ the
/// transversal(s) at the run's start/end reparametrised outward from the vertex, v > 0 on
/// the left of the run, v < 0 on the right (the transversal continued through the vertex).
/// Both transversals take the same v, in their own parameter units (the thesis leaves the units
/// open). u~ and v are jets in the domain coordinates.
VectorJet runSweep(const CurveNetwork& network, int run, const Jet& uTilde, const Jet& v);

/// The patch of face `face` at domain point p of the regular N-gon (N = #sides), with first
/// and second derivatives in (x, y): Q = sum_i B_i^m S_i (eq. (5.3)), S_i the sub-surface of side
/// i from its run sweep with u~_run = rho0 + (rho1 - rho0) u~_i (forward; mirrored backward) and
/// v = +-F_i(u~_i) d_i, F_i = Delta_{i-1}(1 - u~) + Delta_{i+1} u~ (eq. (5.1)).
/// At an exact domain vertex the value is the network vertex and the derivatives are zero
/// (A6: derivatives are direction dependent there; use the vertex normal).
/// @param p domain point inside or on the regular N-gon of NGonDomain(N).
VectorJet evaluatePatch(const CurveNetwork& network, int face, const NGonDomain& domain,
                        const Eigen::Vector2d& p, const PatchOptions& options = {});

/// Unit normal Q_x x Q_y / |.| from a jet (zero vector if degenerate).
Eigen::Vector3d patchNormal(const VectorJet& q);

}  // namespace ffdkit::geometry::curvenet
