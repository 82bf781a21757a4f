#pragma once

#include <Eigen/Core>

#include "ffdkit/geometry/tessellation.h"

namespace ffdkit::geometry::quaternion {

/// A space curve parameterised by arc length s in [0, length()]. All three quaternion curve
/// models (QI interpolation, QI fitting chains, sphere-tangent curves) implement it so that
/// sampling, plotting and curvature combs are written once.
class ArcLengthCurve {
 public:
  virtual ~ArcLengthCurve() = default;
  /// Total arc length (same length units as the positions).
  virtual double length() const = 0;
  /// Position C(s); s is clamped to [0, length()].
  virtual Eigen::Vector3d position(double s) const = 0;
  /// Unit tangent C'(s).
  virtual Eigen::Vector3d tangent(double s) const = 0;
  /// Unsigned curvature |C''(s)| in 1/length units. At a joint the value of the later piece.
  virtual double curvature(double s) const = 0;
  /// Torsion in 1/length units; a right-handed helix has tau > 0. 0 where the curvature
  /// vanishes (undefined there; a plot shows 0 rather than NaN).
  virtual double torsion(double s) const = 0;
  /// Curvature vector C''(s) = kappa N (zero on straight pieces).
  virtual Eigen::Vector3d curvatureVector(double s) const = 0;
  /// `count` >= 2 positions at equally spaced arc lengths from 0 to length(), one per row.
  /// The default calls position(); models override it with a cumulative integral.
  virtual Eigen::MatrixX3d samplePositions(int count) const;
};

/// Curvature and torsion against arc length at equally spaced samples, for plots and combs.
struct CurveProfile {
  Eigen::VectorXd arcLength;   ///< #samples, from 0 to length
  Eigen::MatrixX3d points;     ///< #samples x 3
  Eigen::VectorXd curvature;   ///< #samples, 1/length units
  Eigen::VectorXd torsion;     ///< #samples, 1/length units
  Eigen::MatrixX3d normals;    ///< #samples x 3 unit principal normals (zero where kappa = 0)
};

/// Samples a curve at `samples` >= 2 equally spaced arc lengths.
/// @throws QuaternionCurveError if samples < 2.
CurveProfile sampleProfile(const ArcLengthCurve& curve, int samples);

/// The curve as an open polyline of `samples` >= 2 points (equally spaced in arc length).
/// @throws QuaternionCurveError if samples < 2.
Polyline toPolyline(const ArcLengthCurve& curve, int samples);

/// A curvature comb: for each profile sample, the tooth tip point - scale * kappa * N (the
/// convention of Sakiyama et al. 2001's radius-of-curvature combs is outward, away from the
/// centre).
/// @return #samples x 3 tooth tips; the tooth roots are profile.points.
Eigen::MatrixX3d curvatureCombTips(const CurveProfile& profile, double scale);

}  // namespace ffdkit::geometry::quaternion
