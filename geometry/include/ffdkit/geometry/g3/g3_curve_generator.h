#pragma once

#include <vector>

#include <Eigen/Core>

#include "ffdkit/geometry/g3/condition.h"
#include "ffdkit/geometry/g3/g3_curve_solver.h"
#include "ffdkit/geometry/g3/quadratic_curvature_spline.h"
#include "ffdkit/geometry/tessellation.h"

namespace ffdkit::geometry::g3 {

/// Parameters of the scenes generator `g3-curve`: everything needed to regenerate the curve
/// at any sampling density. Plain data (Custom conditions aside, which scenes do not offer).
struct G3CurveParams {
  /// Data points p_0..p_n in the plane, n >= 1, consecutive points distinct.
  std::vector<Eigen::Vector2d> points;
  /// Boundary / side conditions; default: the paper's appendix default B10 (kappa_0 = kappa_n = 0
  /// in linear form, 2 rows, min-norm solution). Prefer 3 rows for a unique curve.
  std::vector<Condition> conditions = {Condition::naturalEnds()};
  G3SolverOptions solver;  ///< defaults: damped Newton, continuation on failure
  /// 0: the G3 curve itself; k >= 1: its clothoid approximation with 2^k arcs per span
  /// (1: bi-clothoid, 2: the paper's 4-clothoid refinement).
  int clothoidLevels = 0;
  double z = 0.0;  ///< height of the curve's plane in the 3D polyline

  /// @throws G3InputError naming the offending field.
  void validate() const;
};

/// Sampling of a generated curve.
struct G3CurveSampling {
  int samplesPerSpan = 32;  ///< equal arc-length steps per span (per arc for clothoid output: samplesPerSpan / 2^k, >= 2)
};

/// Solves the curve of params (throws when it does not converge).
/// @throws G3InputError for invalid params; G3SolveError with the solver's message when the
///   solve fails (e.g. the infeasible Fig. 2(d) set-up).
QuadraticCurvatureSpline buildG3Curve(const G3CurveParams& params);

/// Samples of the generated curve against arc length: points, tangent angle, curvature and its
/// derivative (piecewise constant sharpness for clothoid output), for polylines, curvature
/// plots and combs. Deterministic. Throws as buildG3Curve, or G3InputError for samplesPerSpan < 1.
CurveSamples sampleG3Curve(const G3CurveParams& params, const G3CurveSampling& sampling = {});

/// The `g3-curve` deformable object: the sampled curve as an open polyline in the plane z.
/// Throws as sampleG3Curve.
geometry::Polyline generateG3Curve(const G3CurveParams& params, const G3CurveSampling& sampling = {});

}  // namespace ffdkit::geometry::g3
