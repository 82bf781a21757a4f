#pragma once

// Parameter sets and generator functions for the scenes module (issue 9 item 4): each
// generator is deterministic in (params, sampling), so a generated object can keep its
// parameters and be regenerated at another density. Scene generator names:
//   s-spline-curve       -> SSplineCurveParams        / generateSSplineCurve
//   sigma-spline-curve   -> SigmaSplineCurveParams    / generateSigmaSplineCurve
//   s-spline-surface     -> SSplineSurfaceParams      / generateSSplineSurface
//   sigma-spline-surface -> SigmaSplineSurfaceParams  / generateSigmaSplineSurface
//   spline-blend         -> SplineBlendParams         / generateSplineBlend
// Point grids come inline or from a file via readPointGrid (point_grid.h).

#include <Eigen/Core>

#include "ffdkit/geometry/cardinal/curve_curvature.h"
#include "ffdkit/geometry/cardinal/point_grid.h"
#include "ffdkit/geometry/cardinal/s_spline_curve.h"
#include "ffdkit/geometry/cardinal/s_spline_surface.h"
#include "ffdkit/geometry/cardinal/shape_points.h"
#include "ffdkit/geometry/cardinal/sigma_blend.h"
#include "ffdkit/geometry/cardinal/sigma_curve.h"
#include "ffdkit/geometry/cardinal/sigma_surface.h"
#include "ffdkit/geometry/cardinal/surface_tessellation.h"
#include "ffdkit/geometry/tessellation.h"

namespace ffdkit::geometry::cardinal {

/// How densely a curve is sampled.
struct CurveSampling {
  int samplesPerSpan = 16;  ///< sub-intervals per knot interval (>= 1)
};

/// How sigma-spline knots are placed when none are given.
enum class KnotSpacing {
  Uniform,      ///< t_i = i
  ChordLength,  ///< t_{i+1} - t_i = |P_{i+1} - P_i| (surfaces: averaged over the other direction)
};

// ---- S-spline ------------------------------------------------------------------------------

/// Parameters of the S-spline curve generator.
struct SSplineCurveParams {
  Eigen::MatrixX3d points;       ///< data points, one per row (>= 2 open, >= 3 closed)
  SSplineCurveOptions options;   ///< beta2 = 0, halfWidth = 4, open ends by default
  /// @throws CardinalSplineError with the field name on invalid data.
  void validate() const;
};

/// Samples the S-spline curve at samplesPerSpan points per unit parameter interval.
/// Polyline.closed follows the end rule (no duplicated closing point).
Polyline generateSSplineCurve(const SSplineCurveParams& params, const CurveSampling& sampling = {});
/// Curvature and torsion against arc length at the same samples (right-hand derivatives).
CurvatureSamples sSplineCurveCurvature(const SSplineCurveParams& params,
                                       const CurveSampling& sampling = {});

/// Parameters of the S-spline surface generator.
struct SSplineSurfaceParams {
  PointGrid points;               ///< >= 2 x 2 grid (>= 3 along closed directions)
  SSplineSurfaceOptions options;  ///< beta2 = 0, halfWidth = 4, open in u and v by default
  /// @throws CardinalSplineError with the field name on invalid data.
  void validate() const;
};

TriangleMesh generateSSplineSurface(const SSplineSurfaceParams& params,
                                    const SurfaceSampling& sampling = {});
/// The same tessellation with per-vertex unit normals (zebra / reflection-line display).
SurfaceTessellation generateSSplineSurfaceWithNormals(const SSplineSurfaceParams& params,
                                                      const SurfaceSampling& sampling = {});

// ---- sigma-spline --------------------------------------------------------------------------

/// Parameters of the sigma-spline curve generator.
struct SigmaSplineCurveParams {
  Eigen::MatrixX3d points;  ///< interpolation points (>= 2 open, >= 3 closed, distinct when closed)
  Eigen::VectorXd knots;    ///< #points values (open) or #points + 1 (closed); empty: `spacing`
  KnotSpacing spacing = KnotSpacing::Uniform;  ///< knot placement when `knots` is empty
  Eigen::VectorXd beta2;    ///< tension per knot (#points values), empty = all 0
  bool closed = false;  ///< a closed (periodic) curve
  ShapeMode shape = ShapeMode::Cubic;  ///< how the shape points are chosen
  EndSlopes endSlopes;                 ///< cubic mode, open curves; default chord rule
  /// @throws CardinalSplineError with the field name on invalid data.
  void validate() const;
};

/// The sigma-spline curve the parameters describe.
SigmaCurve buildSigmaCurve(const SigmaSplineCurveParams& params);
Polyline generateSigmaSplineCurve(const SigmaSplineCurveParams& params,
                                  const CurveSampling& sampling = {});
CurvatureSamples sigmaSplineCurveCurvature(const SigmaSplineCurveParams& params,
                                           const CurveSampling& sampling = {});

/// Parameters of the sigma-spline surface generator.
struct SigmaSplineSurfaceParams {
  PointGrid points;         ///< interpolation grid (>= 2 per open direction, >= 3 closed)
  Eigen::VectorXd knotsU;   ///< rows (+1 if closed) values; empty: `spacing`
  Eigen::VectorXd knotsV;   ///< cols (+1 if closed) values; empty: `spacing`
  KnotSpacing spacing = KnotSpacing::Uniform;  ///< knot placement when knotsU / knotsV are empty
  Eigen::VectorXd beta2U;   ///< tension per u-knot, empty = 0
  Eigen::VectorXd beta2V;   ///< tension per v-knot, empty = 0
  bool closedU = false;  ///< periodic along u
  bool closedV = false;  ///< periodic along v
  SigmaSurfaceOptions shape;  ///< ShapeMode::Cubic (bicubic, consistent corner rule) by default
  /// @throws CardinalSplineError with the field name on invalid data.
  void validate() const;
};

SigmaSurface buildSigmaSurface(const SigmaSplineSurfaceParams& params);
TriangleMesh generateSigmaSplineSurface(const SigmaSplineSurfaceParams& params,
                                        const SurfaceSampling& sampling = {});
SurfaceTessellation generateSigmaSplineSurfaceWithNormals(const SigmaSplineSurfaceParams& params,
                                                          const SurfaceSampling& sampling = {});

// ---- blend ---------------------------------------------------------------------------------

enum class BlendPart {
  Composite,  ///< surface 1 + blend + surface 2 as one mesh
  BlendOnly,  ///< the two blend intervals only
};

/// Parameters of the spline-blend generator: two sigma-spline surfaces joined by a blend.
struct SplineBlendParams {
  SigmaSplineSurfaceParams first;   ///< must be open in v
  SigmaSplineSurfaceParams second;  ///< must be open in v, same u range/closedness as first
  BlendOptions blend;               ///< gaps default to the neighbouring v-intervals
  BlendPart part = BlendPart::Composite;  ///< the composite or the blend alone
  /// @throws CardinalSplineError with the field name on invalid data.
  void validate() const;
};

BlendResult buildSplineBlend(const SplineBlendParams& params);
TriangleMesh generateSplineBlend(const SplineBlendParams& params,
                                 const SurfaceSampling& sampling = {});
SurfaceTessellation generateSplineBlendWithNormals(const SplineBlendParams& params,
                                                   const SurfaceSampling& sampling = {});

}  // namespace ffdkit::geometry::cardinal
