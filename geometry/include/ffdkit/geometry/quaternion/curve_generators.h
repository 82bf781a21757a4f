#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/geometry/quaternion/arc_length_curve.h"
#include "ffdkit/geometry/quaternion/qi_fitting.h"
#include "ffdkit/geometry/quaternion/qi_interpolation.h"
#include "ffdkit/geometry/quaternion/sphere_tangent_fit.h"
#include "ffdkit/geometry/tessellation.h"

namespace ffdkit::geometry::quaternion {

// Generators for scenes: `qi-interpolate`, `qi-fit`, `sphere-tangent`. Each takes plain parameters
// (what a scene file stores) and a sampling density, is deterministic, and throws
// QuaternionCurveError (message prefixed with the generator name) when the parameters are invalid or
// the solver finds no curve: a generator never returns a silently wrong curve.

/// How densely a generated curve is sampled; regenerate at another density with the same params.
struct CurveSampling {
  int samples = 256;  ///< polyline points, equally spaced in arc length (>= 2)
};

/// `qi-interpolate` (Miura 1998): G2 QI curve through points.
struct QiInterpolateParams {
  Eigen::MatrixX3d points;        ///< #P x 3, #P >= 2 (>= 3 for Circle3); default: empty (must be set)
  InterpolationOptions options;   ///< end rule (default Circle3), Newton settings
  void validate() const;          ///< @throws QuaternionCurveError
};

/// `qi-fit` (Sakiyama et al. 2001): G1 chain of QI segments fitted to (noisy) points.
struct QiFitParams {
  Eigen::MatrixX3d points;        ///< #P x 3
  std::vector<int> breaks;        ///< 0 = b_0 < ... < b_M = #P - 1, one segment per interval
  FitOptions options;             ///< degree 2, LSQ-cubic initial guess, fixed start (defaults)
  void validate() const;          ///< @throws QuaternionCurveError
};

/// `sphere-tangent` (Sphere-tangent report): one segment between given end points and tangents.
struct SphereTangentParams {
  SphereTangentSegmentSpec segment;  ///< end conditions, degree 2 or 3
  NelderMeadOptions options;         ///< simplex settings
  void validate() const;             ///< @throws QuaternionCurveError
};

/// Solves and returns the arc-length curve (for profiles, combs and several samplings).
/// @throws QuaternionCurveError on invalid params or when the solver does not converge.
std::shared_ptr<const ArcLengthCurve> solveQiInterpolate(const QiInterpolateParams& params);
std::shared_ptr<const ArcLengthCurve> solveQiFit(const QiFitParams& params);
std::shared_ptr<const ArcLengthCurve> solveSphereTangent(const SphereTangentParams& params);

/// The generated curve as a deformable polyline (sampling.samples points).
/// @throws QuaternionCurveError as the solve functions, or if sampling.samples < 2.
Polyline generateQiInterpolate(const QiInterpolateParams& params, const CurveSampling& sampling = {});
Polyline generateQiFit(const QiFitParams& params, const CurveSampling& sampling = {});
Polyline generateSphereTangent(const SphereTangentParams& params, const CurveSampling& sampling = {});

/// Curvature and torsion against arc length (sampling.samples points), for plots and combs.
CurveProfile profileQiInterpolate(const QiInterpolateParams& params, const CurveSampling& sampling = {});
CurveProfile profileQiFit(const QiFitParams& params, const CurveSampling& sampling = {});
CurveProfile profileSphereTangent(const SphereTangentParams& params, const CurveSampling& sampling = {});

/// Parameter sets of the example scenes (see docs/geometry-quaternion.md).
QiInterpolateParams exampleQiInterpolateParams();  ///< 7 points, Circle3 (Miura 1998, Ex. 3 size)
QiFitParams exampleQiFitParams();                  ///< noisy sine, 31 points, 4 segments (Sakiyama et al. 2001, Ex. 1)
SphereTangentParams exampleSphereTangentParams();  ///< quadratic fit (1,1,1) / (0,0,1) (Sphere-tangent report, Fig. 15)

}  // namespace ffdkit::geometry::quaternion
