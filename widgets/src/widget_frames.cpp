#include "widget_model_impl.h"

namespace ffdkit::widgets {

namespace detail {

void fail(WidgetErrorCode code, const std::string& message) { throw WidgetError(code, message); }


// Rigid part and mean scale of an affine map (polar decomposition, via SVD).
WidgetFrame rigidPart(const Eigen::Affine3d& a) {
  WidgetFrame f;
  f.frame.translation() = a.translation();
  const Eigen::Matrix3d l = a.linear();
  const double det = l.determinant();
  f.size = std::cbrt(std::abs(det));
  const Eigen::Matrix3d ltl = l.transpose() * l;
  const double s2 = ltl.trace() / 3.0;
  if (det > 0 && (ltl - s2 * Eigen::Matrix3d::Identity()).norm() <= 1e-13 * s2) {
    f.frame.linear() = l / std::sqrt(s2);  // a similarity: the common case, no SVD needed
    return f;
  }
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(l, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  f.frame.linear() = svd.matrixU() * d * svd.matrixV().transpose();
  return f;
}

// The local motion D(delta) of an affine widget in its own frame (Kuriyama 1996, sec. 6.2.1).
Eigen::Affine3d localMotion(AffineKind kind, double delta) {
  Eigen::Affine3d d = Eigen::Affine3d::Identity();
  switch (kind) {
    case AffineKind::Translate: d.translation().x() = delta; break;
    case AffineKind::Rotate: d.linear() = Eigen::AngleAxisd(delta, Eigen::Vector3d::UnitZ()).toRotationMatrix(); break;
    case AffineKind::Scale: d.linear() *= std::exp(delta); break;
  }
  return d;
}

// Cell <-> cell transfer (Kuriyama 1996, sec. 6.2.2): the same translation vector, the same
// rotation about the target's centroid, the same per-axis scale in the target's axes, as far as the
// mask allows.
Eigen::Affine3d transferMotion(const Eigen::Affine3d& m, const Eigen::Vector3d& sourceCentroid,
                               const Eigen::Matrix3d& sourceAxes, const Eigen::Vector3d& targetCentroid,
                               const Eigen::Matrix3d& targetAxes, AffineMask mask) {
  const Eigen::Vector3d t = m * sourceCentroid - sourceCentroid;
  const WidgetFrame polar = rigidPart(m);
  const Eigen::Matrix3d r = polar.frame.linear();
  Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();
  if (mask.rotate) linear = r;
  if (mask.scale) {
    const Eigen::Matrix3d k = r.transpose() * m.linear();
    const Eigen::Vector3d s = (sourceAxes.transpose() * k * sourceAxes).diagonal();
    linear = linear * targetAxes * s.asDiagonal() * targetAxes.transpose();
  }
  Eigen::Affine3d out = Eigen::Affine3d::Identity();
  out.linear() = linear;
  out.translation() = targetCentroid + (mask.translate ? t : Eigen::Vector3d::Zero()) - linear * targetCentroid;
  return out;
}

std::string defaultShape(AffineKind kind) {
  switch (kind) {
    case AffineKind::Translate: return "arrow";
    case AffineKind::Rotate: return "ring";
    case AffineKind::Scale: return "cube";
  }
  return "arrow";
}

double wrapAngle(double a) {
  const double twoPi = 2.0 * std::numbers::pi;
  a = std::fmod(a + std::numbers::pi, twoPi);
  if (a < 0) a += twoPi;
  return a - std::numbers::pi;
}

}  // namespace detail

}  // namespace ffdkit::widgets
