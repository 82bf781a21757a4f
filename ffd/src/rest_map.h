// Internal to ffd/: the rest lattice as the map Xbar(u, v, w) and its Jacobian (Kuriyama 1996,
// eq. (6.1) on the rest points), evaluated cell by cell from contiguous windows of control
// points. What Newton on Xbar(uvw) = Q (rest_solver.h) evaluates many times per point.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/ffd/lattice.h"

#include "cell_locator.h"
#include "cell_polynomials.h"
#include "vector_clones.h"

namespace ffdkit::ffd::detail {

constexpr int kMaxBasis = 33;

// x, y, z and a zero: one point of a cell window, one AVX register (two SSE2 registers); the
// type of cell_polynomials.h (aligned to 32 explicitly, see there).
using Xyz0 = Lane4;

// Xbar and dXbar/duvw on a lattice's rest points; thread-safe, no allocation per call.
class RestMap {
 public:
  explicit RestMap(const Lattice& lattice)
      : lattice_(lattice),
        locate_{CellLocator(lattice.axis(0)), CellLocator(lattice.axis(1)), CellLocator(lattice.axis(2))} {
    cubic_ = true;
    for (int a = 0; a < 3; ++a) {
      axis_[a] = &lattice.axis(a);
      lo_[a] = axis_[a]->domainMin();
      hi_[a] = axis_[a]->domainMax();
      cubic_ = cubic_ && CellPolynomials::supports(*axis_[a]);
      periodic_[a] = axis_[a]->periodic();
    }
    if (cubic_) {
      for (int a = 0; a < 3; ++a) poly_[a] = CellPolynomials(*axis_[a]);
    }
    range_ = hi_ - lo_;
    rational_ = lattice.restIsRational();
    buildWindows(lattice.restPoints(), lattice.restWeights());
  }

  // The basis values and derivatives of one parameter point, kept so that the Jacobian is only
  // computed for iterates Newton goes on from (not for the last, converged one).
  struct Basis {
    int cell[3];
    // Degree <= 3 on every axis (cubic()): lane r of n4 / d4 for the r-th function of the cell,
    // and s[c][b] = sum_a N_a(u) P_abc, the partial sums the Jacobian reuses.
    Lane4 n4[3], d4[3];
    Xyz0 s[4][4];
    // Any degree: the Cox-de Boor values and derivatives.
    double N[3][kMaxBasis];
    double D[3][kMaxBasis];
    // Rational rest lattice: the homogeneous sum (sum B w P, sum B w) whose ratio is Xbar.
    Xyz0 h;
  };

  // Xbar(uvw), filling `basis`. The x, y, z of a window point share one vector register, so each
  // basis product is one multiply-add for all three.
  FFDKIT_INLINE Eigen::Vector3d value(const Eigen::Vector3d& uvw, Basis& basis) const {
    if (cubic_) return valueCubic(uvw, basis);
    for (int a = 0; a < 3; ++a) {
      const double t = wrap(a, uvw[a]);
      basis.cell[a] = locate_[a](t);
      axis_[a]->basis(basis.cell[a], t, basis.N[a], basis.D[a]);
    }
    const int nu = axis_[0]->degree() + 1;
    const int nv = axis_[1]->degree() + 1;
    const int nw = axis_[2]->degree() + 1;
    const Xyz0* W = window(basis);
    Xyz0 x = {0, 0, 0, 0};
    for (int c = 0; c < nw; ++c) {
      for (int b = 0; b < nv; ++b) {
        Xyz0 s = {0, 0, 0, 0};
        for (int a = 0; a < nu; ++a, ++W) s += basis.N[0][a] * *W;
        x += (basis.N[1][b] * basis.N[2][c]) * s;
      }
    }
    return result(x, basis);
  }

  // dXbar/duvw at the point `basis` was filled for by value().
  FFDKIT_INLINE Eigen::Matrix3d jacobian(const Basis& basis) const {
    if (cubic_) return jacobianCubic(basis);
    const int nu = axis_[0]->degree() + 1;
    const int nv = axis_[1]->degree() + 1;
    const int nw = axis_[2]->degree() + 1;
    const Xyz0* W = window(basis);
    Xyz0 ju = {0, 0, 0, 0}, jv = ju, jw = ju;
    for (int c = 0; c < nw; ++c) {
      for (int b = 0; b < nv; ++b) {
        Xyz0 s = {0, 0, 0, 0}, su = s;
        for (int a = 0; a < nu; ++a, ++W) {
          s += basis.N[0][a] * *W;
          su += basis.D[0][a] * *W;
        }
        ju += (basis.N[1][b] * basis.N[2][c]) * su;
        jv += (basis.D[1][b] * basis.N[2][c]) * s;
        jw += (basis.N[1][b] * basis.D[2][c]) * s;
      }
    }
    return derivative(ju, jv, jw, basis);
  }

  // Xbar(uvw) and its Jacobian J.
  Eigen::Vector3d evaluate(const Eigen::Vector3d& uvw, Eigen::Matrix3d& J) const {
    Basis basis;
    const Eigen::Vector3d x = value(uvw, basis);
    J = jacobian(basis);
    return x;
  }

  // AxisSpline::wrap, forced inline: Newton calls it several times per iteration, and once the
  // solver's clones grew, GCC stopped inlining the plain inline function (5 % more instructions).
  FFDKIT_INLINE double wrap(int a, double t) const {
    if (!periodic_[a]) return t;
    const double w = t - std::floor(t);
    return w >= 1.0 ? 0.0 : w;
  }

  // The control points of the cell `basis` lies in (x, y, z, 0 per point, a fastest).
  FFDKIT_INLINE const Xyz0* window(const Basis& basis) const {
    return &windows_.data()->point +
           windowSize_ * (basis.cell[0] + cells_[0] * (basis.cell[1] + static_cast<std::size_t>(cells_[1]) * basis.cell[2]));
  }
  // The first cell's control points (the only cell of a single-cell lattice).
  const Xyz0* firstWindow() const { return &windows_.data()->point; }

  const AxisSpline& axis(int a) const { return *axis_[a]; }
  const CellLocator& locator(int a) const { return locate_[a]; }
  // The cells' basis polynomials per axis; cubic() only.
  const CellPolynomials* polynomials() const { return poly_; }
  // Degree <= 3 on every axis: value() and jacobian() run on the cells' polynomials.
  bool cubic() const { return cubic_; }
  // Rest weights other than 1: Xbar is a ratio (Lamousin & Waggenspack 1994), not a polynomial.
  bool rational() const { return rational_; }
  int cells(int a) const { return cells_[a]; }
  const Eigen::Vector3d& lo() const { return lo_; }
  const Eigen::Vector3d& hi() const { return hi_; }
  const Eigen::Vector3d& range() const { return range_; }

 private:
  // value() for degree <= 3 on every axis: the basis from the cells' polynomials, the window
  // padded to 4 x 4 x 4 (zero rows beyond the degree), all loop bounds known to the compiler.
  FFDKIT_INLINE Eigen::Vector3d valueCubic(const Eigen::Vector3d& uvw, Basis& basis) const {
    for (int a = 0; a < 3; ++a) {
      const double t = wrap(a, uvw[a]);
      basis.cell[a] = locate_[a](t);
      poly_[a].evaluate(basis.cell[a], t, basis.n4[a], basis.d4[a]);
    }
    const Xyz0* W = window(basis);
    const Lane4 nu = basis.n4[0], nv = basis.n4[1], nw = basis.n4[2];
    Xyz0 x = {0, 0, 0, 0};
    for (int c = 0; c < 4; ++c) {
      Xyz0 y = {0, 0, 0, 0};
      for (int b = 0; b < 4; ++b, W += 4) {
        const Xyz0 s = nu[0] * W[0] + nu[1] * W[1] + nu[2] * W[2] + nu[3] * W[3];
        basis.s[c][b] = s;
        y += nv[b] * s;
      }
      x += nw[c] * y;
    }
    return result(x, basis);
  }

  // jacobian() for degree <= 3, reusing the partial sums valueCubic() kept in basis.s.
  FFDKIT_INLINE Eigen::Matrix3d jacobianCubic(const Basis& basis) const {
    const Xyz0* W = window(basis);
    const Lane4 nv = basis.n4[1], nw = basis.n4[2];
    const Lane4 du = basis.d4[0], dv = basis.d4[1], dw = basis.d4[2];
    Xyz0 ju = {0, 0, 0, 0}, jv = ju, jw = ju;
    for (int c = 0; c < 4; ++c) {
      Xyz0 yu = {0, 0, 0, 0}, yv = yu, y = yu;
      for (int b = 0; b < 4; ++b, W += 4) {
        const Xyz0 su = du[0] * W[0] + du[1] * W[1] + du[2] * W[2] + du[3] * W[3];
        const Xyz0 s = basis.s[c][b];
        yu += nv[b] * su;
        yv += dv[b] * s;
        y += nv[b] * s;
      }
      ju += nw[c] * yu;
      jv += nw[c] * yv;
      jw += dw[c] * y;
    }
    return derivative(ju, jv, jw, basis);
  }

  // Xbar from the window sum x: x itself, or with rest weights its ratio (each window point holds
  // (w P, w): the fourth lane sums the weights).
  FFDKIT_INLINE Eigen::Vector3d result(const Xyz0& x, Basis& basis) const {
    if (!rational_) return Eigen::Vector3d(x[0], x[1], x[2]);
    basis.h = x;
    return Eigen::Vector3d(x[0] / x[3], x[1] / x[3], x[2] / x[3]);
  }

  // dXbar from the derivatives of the window sums: themselves, or with rest weights the quotient
  // rule (dN - Xbar dW^T) / W.
  FFDKIT_INLINE Eigen::Matrix3d derivative(const Xyz0& ju, const Xyz0& jv, const Xyz0& jw, const Basis& basis) const {
    Eigen::Matrix3d J;
    J << ju[0], jv[0], jw[0], ju[1], jv[1], jw[1], ju[2], jv[2], jw[2];
    if (!rational_) return J;
    const double w = basis.h[3];
    const Eigen::Vector3d x(basis.h[0] / w, basis.h[1] / w, basis.h[2] / w);
    return (J - x * Eigen::RowVector3d(ju[3], jv[3], jw[3])) / w;
  }

  // Each cell's rest control points, contiguous (x, y, z per point, a fastest): Newton evaluates
  // Xbar many times per point, and gathering through the lattice's index map dominated it.
  // With cubic_, each window is padded to 4 x 4 x 4 with zero points (their basis lanes are zero).
  void buildWindows(const Eigen::MatrixX3d& rest, const Eigen::VectorXd& weights) {
    const int nu = axis_[0]->degree() + 1;
    const int nv = axis_[1]->degree() + 1;
    const int nw = axis_[2]->degree() + 1;
    const int pad[3] = {cubic_ ? 4 - nu : 0, cubic_ ? 4 - nv : 0, cubic_ ? 4 - nw : 0};
    windowSize_ = static_cast<std::size_t>(nu + pad[0]) * (nv + pad[1]) * (nw + pad[2]);
    for (int a = 0; a < 3; ++a) cells_[a] = axis_[a]->cellCount();
    windows_.reserve(windowSize_ * cells_[0] * cells_[1] * cells_[2]);
    for (int cw = 0; cw < cells_[2]; ++cw)
      for (int cv = 0; cv < cells_[1]; ++cv)
        for (int cu = 0; cu < cells_[0]; ++cu)
          for (int c = 0; c < nw + pad[2]; ++c)
            for (int b = 0; b < nv + pad[1]; ++b)
              for (int a = 0; a < nu + pad[0]; ++a) {
                if (a >= nu || b >= nv || c >= nw) {
                  windows_.push_back({Xyz0{0.0, 0.0, 0.0, 0.0}});
                  continue;
                }
                const Eigen::Index f = lattice_.index(axis_[0]->controlIndex(cu, a), axis_[1]->controlIndex(cv, b),
                                                      axis_[2]->controlIndex(cw, c));
                if (rational_) {
                  const double w = weights[f];
                  windows_.push_back({Xyz0{w * rest(f, 0), w * rest(f, 1), w * rest(f, 2), w}});
                } else {
                  windows_.push_back({Xyz0{rest(f, 0), rest(f, 1), rest(f, 2), 0.0}});
                }
              }
  }

  const Lattice& lattice_;
  const AxisSpline* axis_[3];
  Eigen::Vector3d lo_, hi_, range_;
  CellLocator locate_[3];
  bool periodic_[3] = {false, false, false};
  bool cubic_ = false;  // degree <= 3 on every axis: valueCubic / jacobianCubic
  bool rational_ = false;  // rest weights: windows hold (w P, w) and Xbar is their ratio
  CellPolynomials poly_[3];
  struct alignas(32) WindowPoint {  // a std::vector drops the typedef's alignment, a struct keeps it
    Xyz0 point;
  };
  static_assert(sizeof(WindowPoint) == sizeof(Xyz0));
  std::vector<WindowPoint> windows_;
  std::size_t windowSize_ = 0;
  int cells_[3] = {0, 0, 0};
};

}  // namespace ffdkit::ffd::detail
