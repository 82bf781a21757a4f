// Internal to ffd/: solves Xbar(u,v,w) = Q on a lattice's rest lattice (Kuriyama 1996, eq. (6.2)).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "ffdkit/ffd/embedding.h"
#include "ffdkit/ffd/lattice.h"

#include "cell_locator.h"
#include "cell_polynomials.h"
#include "curvature_bound.h"
#include "cylinder_start.h"
#include "vector_clones.h"

namespace ffdkit::ffd::detail {

constexpr int kMaxBasis = 33;

// x, y, z and a zero: one point of a cell window, one AVX register (two SSE2 registers); the
// type of cell_polynomials.h (aligned to 32 explicitly, see there).
using Xyz0 = Lane4;
// Evaluates Xbar and its Jacobian on the rest lattice; one per thread-safe call, no allocation.
class RestSolver {
 public:
  // inverseGrid: also tabulate the inverse map on a coarse grid for first guesses (worth its
  // ~5000 Newton solves only when many points follow).
  RestSolver(const Lattice& lattice, const EmbedOptions& options, bool inverseGrid = false)
      : lattice_(lattice),
        rest_(lattice.restPoints()),
        options_(options),
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
    tol_ = options.tolerance * lattice.restSize();
    affineInverse_ = lattice.restAffineLinear().inverse();
    if (!affineInverse_.allFinite()) affineInverse_ = Eigen::Matrix3d::Identity();
    cylinder_ = lattice.cylinderRestShape();
    if (cylinder_ && cubic_) cylinderStart_.emplace(lattice, *cylinder_, poly_[1], locate_[1]);
    restMin_ = rest_.colwise().minCoeff().transpose();
    restMax_ = rest_.colwise().maxCoeff().transpose();
    buildWindows();
    if (cubic_) curvature_ = restCurvatureBound(lattice, poly_);
    if (!lattice.restIsAffine()) buildSamples();
    const bool periodic = axis_[0]->periodic() || axis_[1]->periodic() || axis_[2]->periodic();
    wantsInverseGrid_ = inverseGrid && !lattice.restIsAffine() && !cylinder_ && !periodic;
    gridMin_ = restMin_;
    gridScale_ = Eigen::Vector3d::Constant(kGridCells).cwiseQuotient((restMax_ - restMin_).cwiseMax(1e-300));
  }

  // Whether the caller should tabulate the inverse (solveGridNode below): the constructor was
  // asked to and it applies. Left to the caller, which runs it on its threads and in the
  // instruction set's clone (vector_clones.h).
  bool wantsInverseGrid() const { return wantsInverseGrid_ && gridUvw_.empty(); }

  // The basis values and derivatives of one parameter point, kept so that the Jacobian is only
  // computed for iterates Newton goes on from (not for the last, converged one).
  struct Basis {
    int cell[3];
    // Degree <= 3 on every axis (cubic_): lane r of n4 / d4 for the r-th function of the cell,
    // and s[c][b] = sum_a N_a(u) P_abc, the partial sums the Jacobian reuses.
    Lane4 n4[3], d4[3];
    Xyz0 s[4][4];
    // Any degree: the Cox-de Boor values and derivatives.
    double N[3][kMaxBasis];
    double D[3][kMaxBasis];
  };

  // Xbar(uvw) (Kuriyama 1996, eq. (6.1) on the rest points), filling `basis`. The x, y, z of a
  // window point share one vector register, so each basis product is one multiply-add for all
  // three.
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
    return Eigen::Vector3d(x[0], x[1], x[2]);
  }

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
    return Eigen::Vector3d(x[0], x[1], x[2]);
  }

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
    Eigen::Matrix3d J;
    J << ju[0], jv[0], jw[0], ju[1], jv[1], jw[1], ju[2], jv[2], jw[2];
    return J;
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
    Eigen::Matrix3d J;
    J << ju[0], jv[0], jw[0], ju[1], jv[1], jw[1], ju[2], jv[2], jw[2];
    return J;
  }

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

  // Wraps periodic axes, reflects through the axis of a solid cylinder, keeps iterates bounded.
  FFDKIT_INLINE void normalize(Eigen::Vector3d& uvw) const {
    if (cylinder_ && cylinder_->innerRadius == 0.0 && uvw[0] < lo_[0]) {
      if (lattice_.counts()[1] % 2 == 0) {
        // Xbar(lo - d, v) == Xbar(lo + d, v + 1/2) when the ring of control points is point-symmetric.
        uvw[0] = 2.0 * lo_[0] - uvw[0];
        uvw[1] += 0.5;
      } else {
        uvw[0] = lo_[0];
      }
    }
    for (int a = 0; a < 3; ++a) {
      if (axis_[a]->periodic()) {
        uvw[a] = wrap(a, uvw[a]);
      } else {
        uvw[a] = std::clamp(uvw[a], lo_[a] - 2.0 * range_[a], hi_[a] + 2.0 * range_[a]);
      }
    }
  }

  FFDKIT_INLINE Eigen::Vector3d initialGuess(const Eigen::Vector3d& q) const {
    Eigen::Vector3d uvw;
    if (interpolateInverse(q, uvw) || (cylinderStart_ && cylinderStart_->guess(q, uvw))) {
      normalize(uvw);
      return uvw;
    }
    if (cylinder_) {
      const double r = std::hypot(q.x(), q.y());
      const double angle = r > 0.0 ? std::atan2(q.y(), q.x()) : 0.0;
      uvw[0] = lo_[0] + range_[0] * (r - cylinder_->innerRadius) / (cylinder_->outerRadius - cylinder_->innerRadius);
      uvw[1] = angle / (2.0 * std::numbers::pi);
      uvw[2] = lo_[2] + range_[2] * (q.z() - cylinder_->zMin) / (cylinder_->zMax - cylinder_->zMin);
    } else {
      uvw = affineInverse_ * (q - lattice_.restAffineOffset());
    }
    for (int a = 0; a < 3; ++a) {
      if (!std::isfinite(uvw[a])) uvw[a] = 0.5 * (lo_[a] + hi_[a]);
      if (!axis_[a]->periodic()) uvw[a] = std::clamp(uvw[a], lo_[a] - 0.5 * range_[a], hi_[a] + 0.5 * range_[a]);
    }
    normalize(uvw);
    return uvw;
  }

  // Damped Newton; returns true on convergence. uvw: initial guess in, last iterate out.
  FFDKIT_INLINE bool newton(const Eigen::Vector3d& q, Eigen::Vector3d& uvw) const {
    Basis basis[2];
    const Eigen::Vector3d F = value(uvw, basis[0]) - q;
    return iterate(q, uvw, basis, F, std::sqrt(F.squaredNorm()), 0);  // F.norm(), which GCC may not inline
  }

  enum class AfterStep { Converged, Failed, Rejected };
  // newton() from its second iterate: uvw is the first full step from a guess whose residual
  // norm was fGuess (firstSteps() below, normalised). Rejected when that step does not lower the
  // residual: newton() would then have halved it, so the caller starts newton() from the guess.
  FFDKIT_INLINE AfterStep newtonAfterStep(const Eigen::Vector3d& q, Eigen::Vector3d& uvw, double fGuess) const {
    Basis basis[2];
    const Eigen::Vector3d F = value(uvw, basis[0]) - q;
    const double f = F.norm();
    if (!(f < fGuess || f <= tol_)) return AfterStep::Rejected;
    return iterate(q, uvw, basis, F, f, 1) ? AfterStep::Converged : AfterStep::Failed;
  }

  // firstSteps() applies (newton() takes at least two iterations): degree <= 3 on every axis, a single cell (all points share one window
  // and one set of basis polynomials), no periodic axis, not a cylinder (normalize() is a clamp).
  bool batchedFirstStep() const {
    bool ok = cubic_ && !cylinder_ && options_.maxIterations >= 2;
    for (int a = 0; a < 3; ++a) ok = ok && cells_[a] == 1 && !axis_[a]->periodic();
    return ok;
  }
  double tolerance() const { return tol_; }

  // Newton's first two steps for kBatch points at once, one point per vector lane (the per-point
  // solver keeps x, y, z in one register and evaluates the basis once per point and axis), the
  // same arithmetic as newton() up to rounding: F = Xbar(uvw) - q and J = dXbar/duvw at the
  // guesses (Kuriyama 1996, eq. (6.1) with the cell's basis polynomials of cell_polynomials.h),
  // fGuess = |F|, step = uvw - J^-1 F (normalised; NaN where J is nearly singular, where newton()
  // takes a Levenberg-Marquardt step), then at the step the same again: done = 1 where newton()
  // would stop at iteration 1 (the step's residual is within the tolerance, or the next step is
  // certified, see certified()) with its result in `result`. Needs batchedFirstStep(). Each
  // pointer addresses kBatch values.
  static constexpr int kBatch = 8;
  typedef double Lane8 __attribute__((vector_size(kBatch * sizeof(double))));
  FFDKIT_INLINE void firstSteps(const double* qIn[3], const double* uvwIn[3], double* fGuess, double* step[3],
                                double* done, double* result[3]) const {
    Lane8 q[3], t[3], F[3], J[3][3], delta[3], jNorm2;
    for (int a = 0; a < 3; ++a) {
      __builtin_memcpy(&q[a], qIn[a], sizeof(Lane8));
      __builtin_memcpy(&t[a], uvwIn[a], sizeof(Lane8));
    }
    evaluateBatch(t, q, F, J);
    const Lane8 f0 = sqrtBatch(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]);
    __builtin_memcpy(fGuess, &f0, sizeof f0);
    solveBatch(J, F, delta, jNorm2);
    Lane8 t1[3];
    for (int a = 0; a < 3; ++a) {
      t1[a] = clampBatch(t[a] + delta[a], lo_[a] - 2.0 * range_[a], hi_[a] + 2.0 * range_[a]);
      __builtin_memcpy(step[a], &t1[a], sizeof(Lane8));
    }
    evaluateBatch(t1, q, F, J);
    const Lane8 f1 = sqrtBatch(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]);
    solveBatch(J, F, delta, jNorm2);
    // certified() across the lanes: |F + J delta| + rounding + 1/2 sum_ab H_ab |delta_a delta_b|.
    Lane8 r2 = {}, d2 = {}, taylor = {};
    for (int k = 0; k < 3; ++k) {
      const Lane8 r = F[k] + J[k][0] * delta[0] + J[k][1] * delta[1] + J[k][2] * delta[2];
      r2 += r * r;
      d2 += delta[k] * delta[k];
    }
    Lane8 d[3];
    for (int a = 0; a < 3; ++a) d[a] = delta[a] < 0.0 ? -delta[a] : delta[a];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) taylor += curvature_(a, b) * d[a] * d[b];
    taylor *= 0.5;
    constexpr double kRounding = 8.0 * std::numeric_limits<double>::epsilon();
    const Lane8 linear = sqrtBatch(r2) + kRounding * (f1 + sqrtBatch(jNorm2) * sqrtBatch(d2));
    Lane8 x0[3], x1[3], t2[3];
    for (int a = 0; a < 3; ++a) {
      x0[a] = (t1[a] - poly_[a].origin(0)) * poly_[a].scale(0);
      x1[a] = (t1[a] + delta[a] - poly_[a].origin(0)) * poly_[a].scale(0);
      t2[a] = clampBatch(t1[a] + delta[a], lo_[a] - 2.0 * range_[a], hi_[a] + 2.0 * range_[a]);
    }
    for (int i = 0; i < kBatch; ++i) {
      const bool accepted = f1[i] < f0[i] || f1[i] <= tol_;
      bool certain = taylor[i] <= 0.25 * tol_ && taylor[i] + linear[i] <= 0.5 * tol_;
      for (int a = 0; a < 3; ++a) certain = certain && x0[a][i] >= 0.0 && x0[a][i] <= 1.0 && x1[a][i] >= 0.0 && x1[a][i] <= 1.0;
      const bool within = f1[i] <= tol_;
      done[i] = !(f0[i] <= tol_) && accepted && (within || certain) ? 1.0 : 0.0;
      for (int a = 0; a < 3; ++a) result[a][i] = within ? t1[a][i] : t2[a][i];
    }
  }

 private:
  // F = Xbar(t) - q and J[k][a] = dXbar_k / dt_a across kBatch points of the single cell.
  FFDKIT_INLINE void evaluateBatch(const Lane8 t[3], const Lane8 q[3], Lane8 F[3], Lane8 J[3][3]) const {
    // Per axis the values N[r] and derivatives D[r] (d/dt) of the cell's four functions.
    Lane8 N[3][4], D[3][4];
    for (int a = 0; a < 3; ++a) {
      const Lane4* A = poly_[a].coefficients(0);
      const double scale = poly_[a].scale(0);
      const Lane8 x = (t[a] - poly_[a].origin(0)) * scale;
      for (int r = 0; r < 4; ++r) {
        N[a][r] = A[0][r] + x * (A[1][r] + x * (A[2][r] + x * A[3][r]));
        D[a][r] = scale * (A[1][r] + x * (2.0 * A[2][r] + x * (3.0 * A[3][r])));
      }
    }
    const Xyz0* W = &windows_.data()->point;
    Lane8 X[3] = {}, Ju[3] = {}, Jv[3] = {}, Jw[3] = {};
    for (int c = 0; c < 4; ++c) {
      Lane8 y[3] = {}, yu[3] = {}, yv[3] = {};
      for (int b = 0; b < 4; ++b, W += 4) {
        Lane8 s[3] = {}, su[3] = {};
        for (int a = 0; a < 4; ++a) {
          for (int k = 0; k < 3; ++k) {
            s[k] += N[0][a] * W[a][k];
            su[k] += D[0][a] * W[a][k];
          }
        }
        for (int k = 0; k < 3; ++k) {
          y[k] += N[1][b] * s[k];
          yu[k] += N[1][b] * su[k];
          yv[k] += D[1][b] * s[k];
        }
      }
      for (int k = 0; k < 3; ++k) {
        X[k] += N[2][c] * y[k];
        Ju[k] += N[2][c] * yu[k];
        Jv[k] += N[2][c] * yv[k];
        Jw[k] += D[2][c] * y[k];
      }
    }
    for (int k = 0; k < 3; ++k) {
      F[k] = X[k] - q[k];
      J[k][0] = Ju[k];
      J[k][1] = Jv[k];
      J[k][2] = Jw[k];
    }
  }

  // delta = -J^-1 F by cofactors across the lanes, NaN where J is nearly singular (the test of
  // newton(): |det| <= 1e-10 |J|^3, Frobenius norm, whose square is returned in norm2).
  FFDKIT_INLINE static void solveBatch(const Lane8 J[3][3], const Lane8 F[3], Lane8 delta[3], Lane8& norm2) {
    Lane8 C[3][3];  // cofactors: C[a][k] of J[k][a]
    for (int k = 0; k < 3; ++k) {
      const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      for (int a = 0; a < 3; ++a) {
        const int a1 = (a + 1) % 3, a2 = (a + 2) % 3;
        C[a][k] = J[k1][a1] * J[k2][a2] - J[k1][a2] * J[k2][a1];
      }
    }
    const Lane8 det = J[0][0] * C[0][0] + J[0][1] * C[1][0] + J[0][2] * C[2][0];
    norm2 = Lane8{};
    for (int k = 0; k < 3; ++k) norm2 += J[k][0] * J[k][0] + J[k][1] * J[k][1] + J[k][2] * J[k][2];
    Lane8 inv;
    for (int i = 0; i < kBatch; ++i) {
      const double scale3 = norm2[i] * std::sqrt(norm2[i]);
      inv[i] = std::abs(det[i]) > 1e-10 * scale3 ? -1.0 / det[i] : std::numeric_limits<double>::quiet_NaN();
    }
    for (int a = 0; a < 3; ++a) delta[a] = (C[a][0] * F[0] + C[a][1] * F[1] + C[a][2] * F[2]) * inv;
  }

  FFDKIT_INLINE static Lane8 sqrtBatch(Lane8 x) {
    for (int i = 0; i < kBatch; ++i) x[i] = std::sqrt(x[i]);
    return x;
  }
  // std::clamp across the lanes (NaN stays NaN).
  FFDKIT_INLINE static Lane8 clampBatch(Lane8 x, double lo, double hi) {
    for (int i = 0; i < kBatch; ++i) x[i] = std::clamp(x[i], lo, hi);
    return x;
  }

  // Newton's iterations from uvw with F = Xbar(uvw) - q, f = |F|, Xbar's basis in basis[0].
  FFDKIT_INLINE bool iterate(const Eigen::Vector3d& q, Eigen::Vector3d& uvw, Basis basis[2], Eigen::Vector3d F, double f,
                             int first) const {
    int current = 0;
    for (int it = first; it < options_.maxIterations; ++it) {
      if (f <= tol_) return true;
      const Eigen::Matrix3d J = jacobian(basis[current]);
      Eigen::Vector3d delta;
      const double det = J.determinant();
      const double scale = J.norm();
      if (std::abs(det) > 1e-10 * scale * scale * scale) {
        delta = -(J.inverse() * F);
      } else {
        // Levenberg-Marquardt step where the Jacobian is (nearly) singular, e.g. on a cylinder's axis.
        const Eigen::Matrix3d JtJ = J.transpose() * J;
        const double mu = 1e-8 * JtJ.trace() + std::numeric_limits<double>::min();
        delta = -(JtJ + mu * Eigen::Matrix3d::Identity()).ldlt().solve(J.transpose() * F);
      }
      if (!delta.allFinite()) return false;
      if (cubic_ && certified(basis[current], uvw, delta, F, J)) {
        uvw += delta;
        normalize(uvw);
        return true;
      }
      bool accepted = false;
      double step = 1.0;
      for (int halving = 0; halving < 30; ++halving, step *= 0.5) {
        Eigen::Vector3d trial = uvw + step * delta;
        normalize(trial);
        const Eigen::Vector3d Ft = value(trial, basis[1 - current]) - q;
        const double ft = Ft.norm();
        if (ft < f || ft <= tol_) {
          uvw = trial;
          F = Ft;
          f = ft;
          current = 1 - current;
          accepted = true;
          break;
        }
      }
      if (!accepted) return f <= tol_;
    }
    return f <= tol_;
  }

 public:
  // Early exit: true when |Xbar(uvw + delta) - q| <= tol is certain without evaluating Xbar there
  // (Newton's last evaluation only confirmed what the step size already told). uvw and uvw + delta
  // must lie in the closure of the cell `basis` was filled for; there Xbar is one polynomial and
  // Taylor's theorem gives |F(uvw + delta)| <= |F + J delta| + 1/2 sum_ab H_ab |delta_a| |delta_b|
  // with H the curvature bound (curvature_bound.h); the rounding of F + J delta is added, and the
  // bound must stay below half the tolerance.
  FFDKIT_INLINE bool certified(const Basis& basis, const Eigen::Vector3d& uvw, const Eigen::Vector3d& delta,
                               const Eigen::Vector3d& F, const Eigen::Matrix3d& J) const {
    const Eigen::Vector3d d = delta.cwiseAbs();
    const double taylor = 0.5 * d.dot(curvature_ * d);
    if (!(taylor <= 0.25 * tol_)) return false;
    constexpr double kRounding = 8.0 * std::numeric_limits<double>::epsilon();
    const double linear = (F + J * delta).norm() + kRounding * (F.norm() + J.norm() * delta.norm());
    if (!(taylor + linear <= 0.5 * tol_)) return false;
    for (int a = 0; a < 3; ++a) {
      const double x0 = poly_[a].local(basis.cell[a], uvw[a]);
      const double x1 = poly_[a].local(basis.cell[a], uvw[a] + delta[a]);
      if (!(x0 >= 0.0 && x0 <= 1.0 && x1 >= 0.0 && x1 <= 1.0)) return false;
    }
    return true;
  }

  // True when q lies outside the axis-aligned bounding box of the rest points (grown by the
  // tolerance): then it is outside the rest volume, which lies in the convex hull of the rest
  // points (the bases are non-negative and sum to 1), whatever Newton did.
  bool outsideRestHull(const Eigen::Vector3d& q) const {
    return ((q - restMin_).array() < -tol_).any() || ((q - restMax_).array() > tol_).any();
  }

  // The parameters in the box whose rest image is closest to q: projected Gauss-Newton on
  // |Xbar(uvw) - q|^2 from the nearest grid sample. For points outside the rest volume where
  // Newton on Xbar(uvw) = q has no solution (the polynomial's extension never reaches q).
  Eigen::Vector3d closestInBox(const Eigen::Vector3d& q) const {
    Eigen::Vector3d uvw = clampToBox(nearestSample(q));
    Eigen::Matrix3d J;
    Eigen::Vector3d F = evaluate(uvw, J) - q;
    for (int it = 0; it < options_.maxIterations; ++it) {
      const Eigen::Matrix3d JtJ = J.transpose() * J;
      const double mu = 1e-10 * JtJ.trace() + std::numeric_limits<double>::min();
      const Eigen::Vector3d delta = -(JtJ + mu * Eigen::Matrix3d::Identity()).ldlt().solve(J.transpose() * F);
      bool accepted = false;
      for (double step = 1.0; step > 1e-9; step *= 0.5) {
        Eigen::Vector3d trial = uvw + step * delta;
        normalize(trial);
        trial = clampToBox(trial);
        Eigen::Matrix3d Jt;
        const Eigen::Vector3d Ft = evaluate(trial, Jt) - q;
        if (Ft.squaredNorm() < F.squaredNorm()) {
          accepted = (trial - uvw).cwiseAbs().maxCoeff() > 1e-15 * range_.maxCoeff();
          uvw = trial;
          F = Ft;
          J = Jt;
          break;
        }
      }
      if (!accepted) break;
    }
    return uvw;
  }

  // Windows of the cell `basis` lies in.
  FFDKIT_INLINE const Xyz0* window(const Basis& basis) const {
    return &windows_.data()->point +
           windowSize_ * (basis.cell[0] + cells_[0] * (basis.cell[1] + static_cast<std::size_t>(cells_[1]) * basis.cell[2]));
  }

  // Trilinear interpolation of the tabulated inverse map; false outside the grid or next to a
  // node that did not converge.
  FFDKIT_INLINE bool interpolateInverse(const Eigen::Vector3d& q, Eigen::Vector3d& uvw) const {
    if (gridUvw_.empty()) return false;
    int i[3];
    double f[3];
    for (int a = 0; a < 3; ++a) {
      const double t = (q[a] - gridMin_[a]) * gridScale_[a];
      if (!(t >= 0.0 && t < kGridCells)) return false;
      i[a] = static_cast<int>(t);
      f[a] = t - i[a];
    }
    constexpr int kNodes = kGridCells + 1;
    const std::size_t base = i[0] + kNodes * (i[1] + static_cast<std::size_t>(kNodes) * i[2]);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int corner = 0; corner < 8; ++corner) {
      const int dx = corner & 1, dy = (corner >> 1) & 1, dz = corner >> 2;
      const std::size_t node = base + dx + kNodes * (dy + static_cast<std::size_t>(kNodes) * dz);
      if (!gridValid_[node]) return false;
      const double w = (dx ? f[0] : 1.0 - f[0]) * (dy ? f[1] : 1.0 - f[1]) * (dz ? f[2] : 1.0 - f[2]);
      sum += w * gridUvw_[node];
    }
    uvw = sum;
    return true;
  }

  // Nearest sample of a coarse parameter grid: the restart point when Newton from the first guess fails.
  FFDKIT_INLINE Eigen::Vector3d nearestSample(const Eigen::Vector3d& q) const {
    double best = std::numeric_limits<double>::infinity();
    Eigen::Vector3d uvw = 0.5 * (lo_ + hi_);
    for (std::size_t s = 0; s < sampleX_.size(); ++s) {
      const double d = (sampleX_[s] - q).squaredNorm();
      if (d < best) {
        best = d;
        uvw = sampleUvw_[s];
      }
    }
    return uvw;
  }

  bool insideBox(const Eigen::Vector3d& uvw) const {
    for (int a = 0; a < 3; ++a) {
      if (axis_[a]->periodic()) continue;
      const double eps = options_.boundaryEpsilon * range_[a];
      if (uvw[a] < lo_[a] - eps || uvw[a] > hi_[a] + eps) return false;
    }
    return true;
  }

  Eigen::Vector3d clampToBox(Eigen::Vector3d uvw) const {
    for (int a = 0; a < 3; ++a) {
      if (!axis_[a]->periodic()) uvw[a] = std::clamp(uvw[a], lo_[a], hi_[a]);
    }
    return uvw;
  }

  const Eigen::Vector3d& lo() const { return lo_; }
  const Eigen::Vector3d& hi() const { return hi_; }

 private:
  // Each cell's rest control points, contiguous (x, y, z per point, a fastest): Newton evaluates
  // Xbar many times per point, and gathering through the lattice's index map dominated it.
  // With cubic_, each window is padded to 4 x 4 x 4 with zero points (their basis lanes are zero).
  void buildWindows() {
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
                windows_.push_back({Xyz0{rest_(f, 0), rest_(f, 1), rest_(f, 2), 0.0}});
              }
  }

  void buildSamples() {
    int n[3];
    for (int a = 0; a < 3; ++a) n[a] = std::min(2 * axis_[a]->cellCount() + 1, 12) + (axis_[a]->periodic() ? 0 : 1);
    Eigen::Matrix3d J;
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i) {
          const int idx[3] = {i, j, k};
          Eigen::Vector3d uvw;
          for (int a = 0; a < 3; ++a) {
            const double t = axis_[a]->periodic() ? double(idx[a]) / n[a] : double(idx[a]) / (n[a] - 1);
            uvw[a] = lo_[a] + range_[a] * t;
          }
          sampleUvw_.push_back(uvw);
          sampleX_.push_back(evaluate(uvw, J));
        }
  }

 public:
  // The tabulated inverse: the inverse map at the nodes of a kGridCells^3 grid over the rest
  // points' bounding box. Interpolated, it starts Newton about 1e-4 from the solution instead of
  // 1e-2 (the affine fit), which saves about one of the four evaluations per point. The caller
  // solves the nodes (solveGridNode, independent, in any order and on any thread) and hands
  // them to setInverseGrid; initialGuess does not use the grid before that.
  static constexpr int kGridCells = 16;
  static constexpr std::int64_t kGridNodes = std::int64_t(kGridCells + 1) * (kGridCells + 1) * (kGridCells + 1);
  FFDKIT_INLINE bool solveGridNode(std::int64_t node, Eigen::Vector3d& uvw) const {
    constexpr int kNodes = kGridCells + 1;
    const std::int64_t i = node % kNodes, j = node / kNodes % kNodes, k = node / (kNodes * kNodes);
    const Eigen::Vector3d q = gridMin_ + Eigen::Vector3d(double(i), double(j), double(k)).cwiseQuotient(gridScale_);
    uvw = initialGuess(q);
    if (newton(q, uvw)) return true;
    uvw = nearestSample(q);
    return newton(q, uvw);
  }
  void setInverseGrid(std::vector<Eigen::Vector3d> uvw, std::vector<char> valid) {
    gridUvw_ = std::move(uvw);
    gridValid_ = std::move(valid);
  }

 private:
  bool wantsInverseGrid_ = false;
  Eigen::Vector3d gridMin_ = Eigen::Vector3d::Zero(), gridScale_ = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> gridUvw_;
  std::vector<char> gridValid_;

  const Lattice& lattice_;
  const Eigen::MatrixX3d& rest_;
  EmbedOptions options_;
  const AxisSpline* axis_[3];
  Eigen::Vector3d lo_, hi_, range_;
  Eigen::Vector3d restMin_, restMax_;  // bounding box of the rest points (local)
  double tol_;
  Eigen::Matrix3d affineInverse_;
  std::optional<CylinderRestShape> cylinder_;
  std::optional<CylinderStart> cylinderStart_;  // untouched cylinders with a cubic angular axis
  CellLocator locate_[3];
  bool periodic_[3] = {false, false, false};
  bool cubic_ = false;  // degree <= 3 on every axis: valueCubic / jacobianCubic
  Eigen::Matrix3d curvature_ = Eigen::Matrix3d::Zero();  // cubic_ only, see certified()
  CellPolynomials poly_[3];
  struct alignas(32) WindowPoint {  // a std::vector drops the typedef's alignment, a struct keeps it
    Xyz0 point;
  };
  static_assert(sizeof(WindowPoint) == sizeof(Xyz0));
  std::vector<WindowPoint> windows_;
  std::size_t windowSize_ = 0;
  int cells_[3] = {0, 0, 0};
  std::vector<Eigen::Vector3d> sampleUvw_;
  std::vector<Eigen::Vector3d> sampleX_;
};

}  // namespace ffdkit::ffd::detail
