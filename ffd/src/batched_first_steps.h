// Internal to ffd/: Newton's first two steps on Xbar(uvw) = q for eight points at once, one
// point per vector lane, on a single-cell lattice of degree <= 3 (rest_solver.h uses it when
// RestSolver::batchedFirstStep() says so; embedding.cpp runs it over runs of points).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Core>

#include "rest_map.h"
#include "vector_clones.h"

namespace ffdkit::ffd::detail {

// The same arithmetic as RestSolver::newton() up to rounding, where the per-point solver keeps
// x, y, z in one register and evaluates the basis once per point and axis: F = Xbar(uvw) - q and
// J = dXbar/duvw at the guesses (Kuriyama 1996, eq. (6.1) with the cell's basis polynomials of
// cell_polynomials.h), fGuess = |F|, step = uvw - J^-1 F (normalised; NaN where J is nearly
// singular, where newton() takes a Levenberg-Marquardt step), then at the step the same again:
// done = 1 where newton() would stop at iteration 1 (the step's residual is within the
// tolerance, or the next step is certified, see RestSolver::certified()) with its result in
// `result`. Each pointer addresses kBatch values.
class BatchedFirstSteps {
 public:
  static constexpr int kBatch = 8;
  typedef double Lane8 __attribute__((vector_size(kBatch * sizeof(double))));

  // map: a single cell of degree <= 3, no periodic axis; tolerance and curvature: the solver's.
  BatchedFirstSteps(const RestMap& map, double tolerance, const Eigen::Matrix3d& curvature)
      : map_(map), tol_(tolerance), curvature_(curvature) {}

  FFDKIT_INLINE void run(const double* qIn[3], const double* uvwIn[3], double* fGuess, double* step[3], double* done,
                         double* result[3]) const {
    const CellPolynomials* poly = map_.polynomials();
    const Eigen::Vector3d& lo = map_.lo();
    const Eigen::Vector3d& hi = map_.hi();
    const Eigen::Vector3d& range = map_.range();
    Lane8 q[3], t[3], F[3], J[3][3], delta[3], jNorm2;
    for (int a = 0; a < 3; ++a) {
      __builtin_memcpy(&q[a], qIn[a], sizeof(Lane8));
      __builtin_memcpy(&t[a], uvwIn[a], sizeof(Lane8));
    }
    evaluate(t, q, F, J);
    const Lane8 f0 = sqrtLanes(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]);
    __builtin_memcpy(fGuess, &f0, sizeof f0);
    solve(J, F, delta, jNorm2);
    Lane8 t1[3];
    for (int a = 0; a < 3; ++a) {
      t1[a] = clampLanes(t[a] + delta[a], lo[a] - 2.0 * range[a], hi[a] + 2.0 * range[a]);
      __builtin_memcpy(step[a], &t1[a], sizeof(Lane8));
    }
    evaluate(t1, q, F, J);
    const Lane8 f1 = sqrtLanes(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]);
    solve(J, F, delta, jNorm2);
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
    const Lane8 linear = sqrtLanes(r2) + kRounding * (f1 + sqrtLanes(jNorm2) * sqrtLanes(d2));
    Lane8 x0[3], x1[3], t2[3];
    for (int a = 0; a < 3; ++a) {
      x0[a] = (t1[a] - poly[a].origin(0)) * poly[a].scale(0);
      x1[a] = (t1[a] + delta[a] - poly[a].origin(0)) * poly[a].scale(0);
      t2[a] = clampLanes(t1[a] + delta[a], lo[a] - 2.0 * range[a], hi[a] + 2.0 * range[a]);
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
  FFDKIT_INLINE void evaluate(const Lane8 t[3], const Lane8 q[3], Lane8 F[3], Lane8 J[3][3]) const {
    const CellPolynomials* poly = map_.polynomials();
    // Per axis the values N[r] and derivatives D[r] (d/dt) of the cell's four functions.
    Lane8 N[3][4], D[3][4];
    for (int a = 0; a < 3; ++a) {
      const Lane4* A = poly[a].coefficients(0);
      const double scale = poly[a].scale(0);
      const Lane8 x = (t[a] - poly[a].origin(0)) * scale;
      for (int r = 0; r < 4; ++r) {
        N[a][r] = A[0][r] + x * (A[1][r] + x * (A[2][r] + x * A[3][r]));
        D[a][r] = scale * (A[1][r] + x * (2.0 * A[2][r] + x * (3.0 * A[3][r])));
      }
    }
    const Xyz0* W = map_.firstWindow();
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
  FFDKIT_INLINE static void solve(const Lane8 J[3][3], const Lane8 F[3], Lane8 delta[3], Lane8& norm2) {
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

  FFDKIT_INLINE static Lane8 sqrtLanes(Lane8 x) {
    for (int i = 0; i < kBatch; ++i) x[i] = std::sqrt(x[i]);
    return x;
  }
  // std::clamp across the lanes (NaN stays NaN).
  FFDKIT_INLINE static Lane8 clampLanes(Lane8 x, double lo, double hi) {
    for (int i = 0; i < kBatch; ++i) x[i] = std::clamp(x[i], lo, hi);
    return x;
  }

  const RestMap& map_;
  double tol_;
  const Eigen::Matrix3d& curvature_;
};

}  // namespace ffdkit::ffd::detail
