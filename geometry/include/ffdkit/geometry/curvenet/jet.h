#pragma once

#include <Eigen/Core>

namespace ffdkit::geometry::curvenet {

/// A scalar with its first and second partial derivatives in the domain coordinates (x, y):
/// the patch evaluator is written once over jets so that values, tangents (G1 tests, normals)
/// and curvatures (G2 tests) come from the same code. @see Kuriyama 1996, sec. 5.3.4 "Derivatives".
struct Jet {
  ///@{
  /// The value, its first partials in x and y, and its second partials.
  double v = 0.0, x = 0.0, y = 0.0, xx = 0.0, xy = 0.0, yy = 0.0;
  ///@}

  /// A constant: all derivatives zero.
  static Jet constant(double c) { return Jet{c, 0, 0, 0, 0, 0}; }
  /// The coordinate x at x0.
  static Jet variableX(double x0) { return Jet{x0, 1, 0, 0, 0, 0}; }
  /// The coordinate y at y0.
  static Jet variableY(double y0) { return Jet{y0, 0, 1, 0, 0, 0}; }
};

inline Jet operator+(const Jet& a, const Jet& b) {
  return {a.v + b.v, a.x + b.x, a.y + b.y, a.xx + b.xx, a.xy + b.xy, a.yy + b.yy};
}
inline Jet operator-(const Jet& a, const Jet& b) {
  return {a.v - b.v, a.x - b.x, a.y - b.y, a.xx - b.xx, a.xy - b.xy, a.yy - b.yy};
}
inline Jet operator-(const Jet& a) { return {-a.v, -a.x, -a.y, -a.xx, -a.xy, -a.yy}; }
inline Jet operator*(double s, const Jet& a) {
  return {s * a.v, s * a.x, s * a.y, s * a.xx, s * a.xy, s * a.yy};
}
inline Jet operator+(double s, const Jet& a) { return {s + a.v, a.x, a.y, a.xx, a.xy, a.yy}; }
inline Jet operator-(double s, const Jet& a) { return {s - a.v, -a.x, -a.y, -a.xx, -a.xy, -a.yy}; }
inline Jet operator*(const Jet& a, const Jet& b) {
  return {a.v * b.v,
          a.x * b.v + a.v * b.x,
          a.y * b.v + a.v * b.y,
          a.xx * b.v + 2.0 * a.x * b.x + a.v * b.xx,
          a.xy * b.v + a.x * b.y + a.y * b.x + a.v * b.xy,
          a.yy * b.v + 2.0 * a.y * b.y + a.v * b.yy};
}
/// Quotient rule; the caller guarantees w.v != 0.
inline Jet operator/(const Jet& u, const Jet& w) {
  Jet q;
  q.v = u.v / w.v;
  q.x = (u.x - q.v * w.x) / w.v;
  q.y = (u.y - q.v * w.y) / w.v;
  q.xx = (u.xx - 2.0 * q.x * w.x - q.v * w.xx) / w.v;
  q.xy = (u.xy - q.x * w.y - q.y * w.x - q.v * w.xy) / w.v;
  q.yy = (u.yy - 2.0 * q.y * w.y - q.v * w.yy) / w.v;
  return q;
}

/// A point of R^3 with its first and second partial derivatives in (x, y).
struct VectorJet {
  ///@{
  /// The point, its first partials in x and y, and its second partials.
  Eigen::Vector3d v = Eigen::Vector3d::Zero(), x = Eigen::Vector3d::Zero(),
                  y = Eigen::Vector3d::Zero(), xx = Eigen::Vector3d::Zero(),
                  xy = Eigen::Vector3d::Zero(), yy = Eigen::Vector3d::Zero();
  ///@}
};

inline VectorJet operator+(const VectorJet& a, const VectorJet& b) {
  return {a.v + b.v, a.x + b.x, a.y + b.y, a.xx + b.xx, a.xy + b.xy, a.yy + b.yy};
}
inline VectorJet operator*(const Jet& s, const VectorJet& p) {
  return {s.v * p.v,
          s.x * p.v + s.v * p.x,
          s.y * p.v + s.v * p.y,
          s.xx * p.v + 2.0 * s.x * p.x + s.v * p.xx,
          s.xy * p.v + s.x * p.y + s.y * p.x + s.v * p.xy,
          s.yy * p.v + 2.0 * s.y * p.y + s.v * p.yy};
}
inline VectorJet operator*(double s, const VectorJet& p) {
  return {s * p.v, s * p.x, s * p.y, s * p.xx, s * p.xy, s * p.yy};
}

/// K(t(x, y)) from K, K', K'' at t.v (chain rule to second order).
inline VectorJet compose(const Eigen::Vector3d& k0, const Eigen::Vector3d& k1,
                         const Eigen::Vector3d& k2, const Jet& t) {
  return {k0,
          k1 * t.x,
          k1 * t.y,
          k2 * (t.x * t.x) + k1 * t.xx,
          k2 * (t.x * t.y) + k1 * t.xy,
          k2 * (t.y * t.y) + k1 * t.yy};
}

}  // namespace ffdkit::geometry::curvenet
