#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Dense>

#include "ffdkit/geometry/curvenet/curve_network.h"
#include "ffdkit/geometry/curvenet/multisided_patch.h"

namespace ffdkit::geometry::curvenet::testing {

/// Largest mismatches across the shared edges of a network (properties P4, P5, P6).
struct EdgeMismatch {
  double position = 0.0;   ///< |Q_f - Q_g| at matched parameters
  double angle = 0.0;      ///< angle between unit normals, rad
  double curvature = 0.0;  ///< |kappa_f(w) - kappa_g(w)| / (1 + |kappa| L) * L  (the P6 scale)
  double boundary = 0.0;   ///< |Q - K(t)| on the side (P1)
  int pairs = 0;           ///< number of (face, face) side pairs compared
};

/// Normal curvature of q in the 3D tangent direction w: a^T II a / a^T I a with [Qx Qy] a = w.
inline double normalCurvature(const VectorJet& q, const Eigen::Vector3d& n, const Eigen::Vector3d& w) {
  Eigen::Matrix<double, 3, 2> j;
  j << q.x, q.y;
  const Eigen::Vector2d a = j.colPivHouseholderQr().solve(w);
  Eigen::Matrix2d first, second;
  first << q.x.dot(q.x), q.x.dot(q.y), q.x.dot(q.y), q.y.dot(q.y);
  second << q.xx.dot(n), q.xy.dot(n), q.xy.dot(n), q.yy.dot(n);
  return a.dot(second * a) / a.dot(first * a);
}

inline Eigen::Vector2d sidePoint(const NGonDomain& d, int side, double s) {
  return (1.0 - s) * d.vertex(side) + s * d.vertex(side + 1);
}

/// Compares, on every run seen by two faces, 5 interior points of the overlap of their sides
/// (avoiding `margin` of the run fraction at the ends) and 6 tangent directions.
/// `other` (default: net) evaluates the second face of each pair, for negative controls.
inline EdgeMismatch sharedEdgeMismatch(const CurveNetwork& net, const PatchOptions& options = {},
                                       double margin = 0.02, const CurveNetwork* other = nullptr) {
  const CurveNetwork& second = other ? *other : net;
  EdgeMismatch out;
  const double length = net.scale;
  for (int f = 0; f < static_cast<int>(net.faces.size()); ++f) {
    const NGonDomain df(static_cast<int>(net.faces[f].sides.size()));
    for (int i = 0; i < df.sides(); ++i) {
      const FaceSide& a = net.faces[f].sides[i];
      if (a.run < 0) continue;  // virtual side of an open region
      const curvenet::Run& run = net.runs[a.run];
      // P1 along this side
      for (int q = 1; q < 8; ++q) {
        const double s = q / 8.0;
        const VectorJet jet = evaluatePatch(net, f, df, sidePoint(df, i, s), options);
        const double span = a.rho1 - a.rho0;
        const double u = a.forward ? a.rho0 + span * s : a.rho1 - span * s;
        const Eigen::Vector3d k = net.curves[run.curve].evaluate(run.tStart + run.delta() * u);
        out.boundary = std::max(out.boundary, (jet.v - k).norm());
      }
      for (int g = f + 1; g < static_cast<int>(net.faces.size()); ++g) {
        const NGonDomain dg(static_cast<int>(net.faces[g].sides.size()));
        for (int j = 0; j < dg.sides(); ++j) {
          const FaceSide& b = net.faces[g].sides[j];
          if (b.run != a.run) continue;
          const double lo = std::max(a.rho0, b.rho0) + margin, hi = std::min(a.rho1, b.rho1) - margin;
          if (!(hi > lo)) continue;
          ++out.pairs;
          for (int q = 0; q < 5; ++q) {
            const double u = lo + (hi - lo) * (q + 0.5) / 5.0;
            const double sa = a.forward ? (u - a.rho0) / (a.rho1 - a.rho0) : (a.rho1 - u) / (a.rho1 - a.rho0);
            const double sb = b.forward ? (u - b.rho0) / (b.rho1 - b.rho0) : (b.rho1 - u) / (b.rho1 - b.rho0);
            const VectorJet qa = evaluatePatch(net, f, df, sidePoint(df, i, sa), options);
            const VectorJet qb = evaluatePatch(second, g, dg, sidePoint(dg, j, sb), options);
            out.position = std::max(out.position, (qa.v - qb.v).norm());
            const Eigen::Vector3d na = patchNormal(qa), nb = patchNormal(qb);
            out.angle = std::max(out.angle, std::atan2(na.cross(nb).norm(), na.dot(nb)));
            const Eigen::Vector3d e1 = net.curves[run.curve].evaluate(run.tStart + run.delta() * u, 1).normalized();
            const Eigen::Vector3d e2 = na.cross(e1).normalized();
            for (int k = 0; k < 6; ++k) {
              const double phi = std::numbers::pi * k / 6.0 + 0.1;
              const Eigen::Vector3d w = std::cos(phi) * e1 + std::sin(phi) * e2;
              const double ka = normalCurvature(qa, na, w), kb = normalCurvature(qb, na, w);
              out.curvature = std::max(out.curvature, std::abs(ka - kb) * length / (1.0 + std::abs(ka) * length));
            }
          }
        }
      }
    }
  }
  return out;
}

}  // namespace ffdkit::geometry::curvenet::testing
