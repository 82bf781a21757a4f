// Internal to ffd/: the inverse rest map of an untouched cylindrical lattice, nearly in closed form.
#pragma once

#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/ffd/lattice.h"
#include "ffdkit/ffd/rest_shape.h"

#include "cell_locator.h"
#include "cell_polynomials.h"
#include "vector_clones.h"

namespace ffdkit::ffd::detail {

// makeCylindricalLattice puts rest point (i, j, k) at (r_i cos t_j, r_i sin t_j, z_k) with r_i and
// z_k linear in the Greville abscissae of the radial (u) and height (w) axes. The tensor-product
// sum then factors (the bases sum to one and reproduce linear functions):
//   Xbar(u, v, w) = ( R(u) / r_out * ring(v),  Z(w) ),   ring(v) = sum_j N_j(v) P_j,
// with R, Z linear and P_j the outer ring of control points (x, y). So w comes from z, v from
// the direction of (x, y) (one scalar equation: ring(v) x (x, y) = 0, Newton from the polar
// angle), and u from the length of (x, y) along ring(v). The caller checks the result with one
// evaluation of Xbar (the lattice's CylinderRestShape is only a hint) and goes on with 3D Newton
// from it when the check fails; one Xbar instead of about four Newton iterations from the polar
// coordinates.
class CylinderStart {
 public:
  // Usable when the angular axis has degree <= 3 (its cell polynomials are given).
  CylinderStart(const Lattice& lattice, const CylinderRestShape& shape, CellPolynomials angular,
                CellLocator locateAngular)
      : shape_(shape), angular_(std::move(angular)), locate_(std::move(locateAngular)) {
    const AxisSpline& v = lattice.axis(1);
    const int outer = lattice.counts()[0] - 1;
    for (int a : {0, 2}) {
      lo_[a] = lattice.axis(a).domainMin();
      range_[a] = lattice.axis(a).domainMax() - lattice.axis(a).domainMin();
    }
    for (int c = 0; c < v.cellCount(); ++c) {
      RingCell cell{{0, 0, 0, 0}, {0, 0, 0, 0}};
      for (int r = 0; r <= v.degree(); ++r) {
        const Eigen::Index f = lattice.index(outer, v.controlIndex(c, r), 0);
        cell.x[r] = lattice.restPoints()(f, 0);
        cell.y[r] = lattice.restPoints()(f, 1);
      }
      ring_.push_back(cell);
    }
  }

  // (u, v, w) with Xbar(u, v, w) = q (local coordinates) for a cylinder as above, to about
  // rounding; false when the angle solve does not settle (the caller then uses its old guess).
  FFDKIT_INLINE bool guess(const Eigen::Vector3d& q, Eigen::Vector3d& uvw) const {
    const double r2 = q.x() * q.x() + q.y() * q.y();
    double v = 0.0, ratio = 0.0;
    if (r2 > 0.0) {
      v = std::atan2(q.y(), q.x()) * (0.5 / std::numbers::pi);
      bool settled = false;
      double px = 0.0, py = 0.0;
      for (int it = 0; it < kMaxIterations && !settled; ++it) {
        v -= std::floor(v);
        if (v >= 1.0) v = 0.0;
        const int c = locate_(v);
        Lane4 N, D;
        angular_.evaluate(c, v, N, D);
        const RingCell& k = ring_[static_cast<std::size_t>(c)];
        const Lane4 nx = N * k.x, ny = N * k.y, dx = D * k.x, dy = D * k.y;
        px = nx[0] + nx[1] + nx[2] + nx[3];
        py = ny[0] + ny[1] + ny[2] + ny[3];
        const double g = px * q.y() - py * q.x();
        const double dg = (dx[0] + dx[1] + dx[2] + dx[3]) * q.y() - (dy[0] + dy[1] + dy[2] + dy[3]) * q.x();
        const double step = -g / dg;
        if (!std::isfinite(step)) return false;
        v += step;
        // Quadratic convergence: after a step this small, v is exact to rounding; (px, py)
        // follows it to first order (the second-order change is below rounding).
        settled = std::abs(step) <= 1e-9;
        px += step * (dx[0] + dx[1] + dx[2] + dx[3]);
        py += step * (dy[0] + dy[1] + dy[2] + dy[3]);
      }
      if (!settled) return false;
      ratio = (px * q.x() + py * q.y()) / (px * px + py * py);
      if (!(ratio >= 0.0)) return false;  // the opposite direction solved the angle equation
    }
    const double radius = ratio * shape_.outerRadius;
    uvw[0] = lo_[0] + range_[0] * (radius - shape_.innerRadius) / (shape_.outerRadius - shape_.innerRadius);
    uvw[1] = v;
    uvw[2] = lo_[2] + range_[2] * (q.z() - shape_.zMin) / (shape_.zMax - shape_.zMin);
    return true;
  }

 private:
  static constexpr int kMaxIterations = 8;
  struct RingCell {
    Lane4 x, y;  // the outer ring's control points of the cell, lane r for the r-th function
  };
  CylinderRestShape shape_;
  CellPolynomials angular_;
  CellLocator locate_;
  double lo_[3] = {0, 0, 0}, range_[3] = {1, 1, 1};
  std::vector<RingCell> ring_;
};

}  // namespace ffdkit::ffd::detail
