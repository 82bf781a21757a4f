#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/geometry/g3/bi_clothoid.h"
#include "ffdkit/geometry/g3/clothoid_arc.h"
#include "ffdkit/geometry/g3/quadratic_curvature_spline.h"

namespace ffdkit::geometry::g3 {

/// Options of the clothoid approximation of a curve.
struct ClothoidApproximationOptions {
  /// 1: a bi-clothoid per span (2 arcs); 2: each span split once more (4 arcs, the paper's
  /// refinement, sec. 6); k: 2^k arcs per span.
  int subdivisionLevels = 1;
  /// Measure Hausdorff distance and curvature deviation per span (costs O(samples^2) per span).
  bool measureErrors = true;
  int errorSamplesPerSpan = 512;  ///< samples of the original span and of its arcs
  BiClothoidOptions fit;          ///< per bi-clothoid Newton
};

/// How well the arcs of one span reproduce it.
struct SpanApproximationError {
  int firstArc = 0;            ///< index into ClothoidApproximation::arcs
  int arcCount = 0;  ///< clothoid arcs used
  double hausdorff = 0.0;      ///< symmetric Hausdorff distance, sampled
  double maxCurvatureDeviation = 0.0;  ///< max |kappa_arcs - kappa|, at proportional arc length
  double lengthDeviation = 0.0;        ///< (sum of arc lengths - Delta s_i) / Delta s_i
  bool converged = true;               ///< every bi-clothoid fit of the span converged
};

/// A curve approximated by clothoid arcs, with its errors.
struct ClothoidApproximation {
  std::vector<ClothoidArc> arcs;               ///< in curve order, G2-joined
  std::vector<SpanApproximationError> spans;   ///< one per span of the G3 curve
  std::vector<double> junctionFractions;       ///< bi-clothoid junction sigma_0/(sigma_0+sigma_1), level 1, per span
  bool converged = true;  ///< every arc met the tolerances
  double maxHausdorff = 0.0;  ///< largest Hausdorff distance of an arc from the curve
  double maxCurvatureDeviation = 0.0;  ///< largest curvature difference from the curve
  /// Spans whose arcs are more than 2 % longer or shorter than the span (
  /// Kuroda et al. 1997 treats that as a warning, not a failure).
  std::vector<std::string> warnings;
};

/// Replaces each span of a G3 curve by clothoid arcs (Kuroda et al. 1997, sec. 6):
/// level 1 fits a bi-clothoid to the span's end points, angles and curvatures; each further
/// level splits every piece at the point of the G3 curve at the same proportional arc length as
/// the bi-clothoid junction (sec. 6: t* = sigma_0/(sigma_0+sigma_1)) and fits both halves.
/// A span that is a clothoid (|a_3| <= 1e-12 (1 + |a_1| + |a_2|)) is reproduced exactly with
/// sigma_0 = sigma_1 = Delta s_i / 2 (the 2x2 system is singular there).
/// @throws G3InputError for subdivisionLevels < 1 or > 8, or errorSamplesPerSpan < 8.
ClothoidApproximation approximateByClothoids(const QuadraticCurvatureSpline& curve,
                                             const ClothoidApproximationOptions& options = {});

/// Samples a chain of arcs: perArc >= 1 steps per arc, (arcs * perArc + 1) x 2 points.
Eigen::MatrixX2d sampleClothoidArcs(const std::vector<ClothoidArc>& arcs, int perArc);

}  // namespace ffdkit::geometry::g3
