#include "ffdkit/geometry/quaternion/arc_length_curve.h"

#include <sstream>

#include "ffdkit/geometry/quaternion/quaternion_error.h"

namespace ffdkit::geometry::quaternion {

namespace {
void requireSamples(const char* where, int samples) {
  if (samples < 2) {
    std::ostringstream msg;
    msg << where << ": expected at least 2 samples, got " << samples;
    throw QuaternionCurveError(msg.str());
  }
}
}  // namespace

Eigen::MatrixX3d ArcLengthCurve::samplePositions(int count) const {
  requireSamples("ArcLengthCurve::samplePositions", count);
  Eigen::MatrixX3d out(count, 3);
  for (int k = 0; k < count; ++k) {
    out.row(k) = position(length() * k / (count - 1)).transpose();
  }
  return out;
}

CurveProfile sampleProfile(const ArcLengthCurve& curve, int samples) {
  requireSamples("sampleProfile", samples);
  CurveProfile p;
  p.arcLength = Eigen::VectorXd::LinSpaced(samples, 0.0, curve.length());
  p.points = curve.samplePositions(samples);
  p.curvature.resize(samples);
  p.torsion.resize(samples);
  p.normals.resize(samples, 3);
  for (int k = 0; k < samples; ++k) {
    const double s = p.arcLength[k];
    const Eigen::Vector3d kn = curve.curvatureVector(s);
    p.curvature[k] = curve.curvature(s);
    p.torsion[k] = curve.torsion(s);
    const double n = kn.norm();
    p.normals.row(k) = (n > 0.0 ? Eigen::Vector3d(kn / n) : Eigen::Vector3d::Zero()).transpose();
  }
  return p;
}

Polyline toPolyline(const ArcLengthCurve& curve, int samples) {
  requireSamples("toPolyline", samples);
  Polyline line;
  line.points = curve.samplePositions(samples);
  line.closed = false;
  return line;
}

Eigen::MatrixX3d curvatureCombTips(const CurveProfile& profile, double scale) {
  Eigen::MatrixX3d tips = profile.points;
  for (Eigen::Index k = 0; k < tips.rows(); ++k) {
    tips.row(k) -= scale * profile.curvature[k] * profile.normals.row(k);
  }
  return tips;
}

}  // namespace ffdkit::geometry::quaternion
