// Internal to ffd/: solves Xbar(u,v,w) = Q on a lattice's rest lattice (Kuriyama 1996, eq. (6.2)):
// first guesses, damped Newton with a certified early exit, and what to do with points Newton
// cannot place. The map itself is rest_map.h; the tabulated inverse, inverse_grid.h; Newton's
// first steps across eight points at once, batched_first_steps.h.
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

#include "batched_first_steps.h"
#include "curvature_bound.h"
#include "cylinder_start.h"
#include "inverse_grid.h"
#include "rest_map.h"
#include "vector_clones.h"

namespace ffdkit::ffd::detail {

// Newton on the rest map for one point at a time; thread-safe calls, no allocation.
class RestSolver {
 public:
  using Basis = RestMap::Basis;
  static constexpr int kBatch = BatchedFirstSteps::kBatch;
  static constexpr int kGridCells = InverseGrid::kCells;
  static constexpr std::int64_t kGridNodes = InverseGrid::kNodes;

  // inverseGrid: also tabulate the inverse map on a coarse grid for first guesses (worth its
  // ~5000 Newton solves only when many points follow).
  RestSolver(const Lattice& lattice, const EmbedOptions& options, bool inverseGrid = false)
      : map_(lattice), lattice_(lattice), options_(options) {
    const Eigen::MatrixX3d& rest = lattice.restPoints();
    tol_ = options.tolerance * lattice.restSize();
    affineInverse_ = lattice.restAffineLinear().inverse();
    if (!affineInverse_.allFinite()) affineInverse_ = Eigen::Matrix3d::Identity();
    cylinder_ = lattice.cylinderRestShape();
    if (cylinder_ && map_.cubic()) cylinderStart_.emplace(lattice, *cylinder_, map_.polynomials()[1], map_.locator(1));
    restMin_ = rest.colwise().minCoeff().transpose();
    restMax_ = rest.colwise().maxCoeff().transpose();
    // The Taylor certificate bounds a polynomial's curvature: not for a rational rest map.
    if (map_.cubic() && !map_.rational()) curvature_ = restCurvatureBound(lattice, map_.polynomials());
    if (!lattice.restIsAffine()) buildSamples();
    const bool periodic = map_.axis(0).periodic() || map_.axis(1).periodic() || map_.axis(2).periodic();
    wantsInverseGrid_ = inverseGrid && !lattice.restIsAffine() && !cylinder_ && !periodic;
    grid_ = InverseGrid(restMin_, restMax_);
  }

  // Whether the caller should tabulate the inverse (solveGridNode below): the constructor was
  // asked to and it applies. Left to the caller, which runs it on its threads and in the
  // instruction set's clone (vector_clones.h).
  bool wantsInverseGrid() const { return wantsInverseGrid_ && grid_.empty(); }
  // Solves node `node` of the tabulated inverse: from the first guess, else from the nearest sample.
  FFDKIT_INLINE bool solveGridNode(std::int64_t node, Eigen::Vector3d& uvw) const {
    const Eigen::Vector3d q = grid_.nodePoint(node);
    uvw = initialGuess(q);
    if (newton(q, uvw)) return true;
    uvw = nearestSample(q);
    return newton(q, uvw);
  }
  // The solved nodes (InverseGrid::set); initialGuess() uses them from then on.
  void setInverseGrid(std::vector<Eigen::Vector3d> uvw, std::vector<char> valid) {
    grid_.set(std::move(uvw), std::move(valid));
  }

  // Xbar(uvw) and its Jacobian J.
  Eigen::Vector3d evaluate(const Eigen::Vector3d& uvw, Eigen::Matrix3d& J) const { return map_.evaluate(uvw, J); }

  // Wraps periodic axes, reflects through the axis of a solid cylinder, keeps iterates bounded.
  FFDKIT_INLINE void normalize(Eigen::Vector3d& uvw) const {
    const Eigen::Vector3d& lo = map_.lo();
    const Eigen::Vector3d& hi = map_.hi();
    const Eigen::Vector3d& range = map_.range();
    if (cylinder_ && cylinder_->innerRadius == 0.0 && uvw[0] < lo[0]) {
      if (lattice_.counts()[1] % 2 == 0) {
        // Xbar(lo - d, v) == Xbar(lo + d, v + 1/2) when the ring of control points is point-symmetric.
        uvw[0] = 2.0 * lo[0] - uvw[0];
        uvw[1] += 0.5;
      } else {
        uvw[0] = lo[0];
      }
    }
    for (int a = 0; a < 3; ++a) {
      if (map_.axis(a).periodic()) {
        uvw[a] = map_.wrap(a, uvw[a]);
      } else {
        uvw[a] = std::clamp(uvw[a], lo[a] - 2.0 * range[a], hi[a] + 2.0 * range[a]);
      }
    }
  }

  // Newton's start: the tabulated inverse or the untouched cylinder's factored inverse when they
  // apply, else the cylindrical coordinates or the least-squares affine fit of the rest lattice.
  FFDKIT_INLINE Eigen::Vector3d initialGuess(const Eigen::Vector3d& q) const {
    const Eigen::Vector3d& lo = map_.lo();
    const Eigen::Vector3d& hi = map_.hi();
    const Eigen::Vector3d& range = map_.range();
    Eigen::Vector3d uvw;
    if (grid_.interpolate(q, uvw) || (cylinderStart_ && cylinderStart_->guess(q, uvw))) {
      normalize(uvw);
      return uvw;
    }
    if (cylinder_) {
      const double r = std::hypot(q.x(), q.y());
      const double angle = r > 0.0 ? std::atan2(q.y(), q.x()) : 0.0;
      uvw[0] = lo[0] + range[0] * (r - cylinder_->innerRadius) / (cylinder_->outerRadius - cylinder_->innerRadius);
      uvw[1] = angle / (2.0 * std::numbers::pi);
      uvw[2] = lo[2] + range[2] * (q.z() - cylinder_->zMin) / (cylinder_->zMax - cylinder_->zMin);
    } else {
      uvw = affineInverse_ * (q - lattice_.restAffineOffset());
    }
    for (int a = 0; a < 3; ++a) {
      if (!std::isfinite(uvw[a])) uvw[a] = 0.5 * (lo[a] + hi[a]);
      if (!map_.axis(a).periodic()) uvw[a] = std::clamp(uvw[a], lo[a] - 0.5 * range[a], hi[a] + 0.5 * range[a]);
    }
    normalize(uvw);
    return uvw;
  }

  // Damped Newton; returns true on convergence. uvw: initial guess in, last iterate out.
  FFDKIT_INLINE bool newton(const Eigen::Vector3d& q, Eigen::Vector3d& uvw) const {
    Basis basis[2];
    const Eigen::Vector3d F = map_.value(uvw, basis[0]) - q;
    return iterate(q, uvw, basis, F, std::sqrt(F.squaredNorm()), 0);  // F.norm(), which GCC may not inline
  }

  enum class AfterStep { Converged, Failed, Rejected };
  // newton() from its second iterate: uvw is the first full step from a guess whose residual
  // norm was fGuess (firstSteps() below, normalised). Rejected when that step does not lower the
  // residual: newton() would then have halved it, so the caller starts newton() from the guess.
  FFDKIT_INLINE AfterStep newtonAfterStep(const Eigen::Vector3d& q, Eigen::Vector3d& uvw, double fGuess) const {
    Basis basis[2];
    const Eigen::Vector3d F = map_.value(uvw, basis[0]) - q;
    const double f = F.norm();
    if (!(f < fGuess || f <= tol_)) return AfterStep::Rejected;
    return iterate(q, uvw, basis, F, f, 1) ? AfterStep::Converged : AfterStep::Failed;
  }

  // firstSteps() applies (newton() takes at least two iterations): degree <= 3 on every axis, a
  // single cell (all points share one window and one set of basis polynomials), no periodic
  // axis, not a cylinder (normalize() is a clamp).
  bool batchedFirstStep() const {
    bool ok = map_.cubic() && !map_.rational() && !cylinder_ && options_.maxIterations >= 2;
    for (int a = 0; a < 3; ++a) ok = ok && map_.cells(a) == 1 && !map_.axis(a).periodic();
    return ok;
  }
  // Newton's first two steps for kBatch points at once (BatchedFirstSteps::run). Needs
  // batchedFirstStep().
  FFDKIT_INLINE void firstSteps(const double* qIn[3], const double* uvwIn[3], double* fGuess, double* step[3],
                                double* done, double* result[3]) const {
    BatchedFirstSteps(map_, tol_, curvature_).run(qIn, uvwIn, fGuess, step, done, result);
  }
  double tolerance() const { return tol_; }

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
    const CellPolynomials* poly = map_.polynomials();
    for (int a = 0; a < 3; ++a) {
      const double x0 = poly[a].local(basis.cell[a], uvw[a]);
      const double x1 = poly[a].local(basis.cell[a], uvw[a] + delta[a]);
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
    Eigen::Vector3d F = map_.evaluate(uvw, J) - q;
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
        const Eigen::Vector3d Ft = map_.evaluate(trial, Jt) - q;
        if (Ft.squaredNorm() < F.squaredNorm()) {
          accepted = (trial - uvw).cwiseAbs().maxCoeff() > 1e-15 * map_.range().maxCoeff();
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

  // Nearest sample of a coarse parameter grid: the restart point when Newton from the first guess fails.
  FFDKIT_INLINE Eigen::Vector3d nearestSample(const Eigen::Vector3d& q) const {
    double best = std::numeric_limits<double>::infinity();
    Eigen::Vector3d uvw = 0.5 * (map_.lo() + map_.hi());
    for (std::size_t s = 0; s < sampleX_.size(); ++s) {
      const double d = (sampleX_[s] - q).squaredNorm();
      if (d < best) {
        best = d;
        uvw = sampleUvw_[s];
      }
    }
    return uvw;
  }

  // Whether uvw lies in the parameter box, grown by the boundary epsilon (periodic axes: always).
  bool insideBox(const Eigen::Vector3d& uvw) const {
    for (int a = 0; a < 3; ++a) {
      if (map_.axis(a).periodic()) continue;
      const double eps = options_.boundaryEpsilon * map_.range()[a];
      if (uvw[a] < map_.lo()[a] - eps || uvw[a] > map_.hi()[a] + eps) return false;
    }
    return true;
  }

  Eigen::Vector3d clampToBox(Eigen::Vector3d uvw) const {
    for (int a = 0; a < 3; ++a) {
      if (!map_.axis(a).periodic()) uvw[a] = std::clamp(uvw[a], map_.lo()[a], map_.hi()[a]);
    }
    return uvw;
  }

  const Eigen::Vector3d& lo() const { return map_.lo(); }
  const Eigen::Vector3d& hi() const { return map_.hi(); }

 private:
  // Newton's iterations from uvw with F = Xbar(uvw) - q, f = |F|, Xbar's basis in basis[0]: a
  // full step (or a Levenberg-Marquardt step where J is nearly singular), certified or halved
  // until the residual drops.
  FFDKIT_INLINE bool iterate(const Eigen::Vector3d& q, Eigen::Vector3d& uvw, Basis basis[2], Eigen::Vector3d F, double f,
                             int first) const {
    int current = 0;
    for (int it = first; it < options_.maxIterations; ++it) {
      if (f <= tol_) return true;
      const Eigen::Matrix3d J = map_.jacobian(basis[current]);
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
      if (map_.cubic() && !map_.rational() && certified(basis[current], uvw, delta, F, J)) {
        uvw += delta;
        normalize(uvw);
        return true;
      }
      bool accepted = false;
      double step = 1.0;
      for (int halving = 0; halving < 30; ++halving, step *= 0.5) {
        Eigen::Vector3d trial = uvw + step * delta;
        normalize(trial);
        const Eigen::Vector3d Ft = map_.value(trial, basis[1 - current]) - q;
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

  // The coarse grid of parameter samples and their rest images (nearestSample()).
  void buildSamples() {
    int n[3];
    for (int a = 0; a < 3; ++a) {
      n[a] = std::min(2 * map_.axis(a).cellCount() + 1, 12) + (map_.axis(a).periodic() ? 0 : 1);
    }
    Eigen::Matrix3d J;
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i) {
          const int idx[3] = {i, j, k};
          Eigen::Vector3d uvw;
          for (int a = 0; a < 3; ++a) {
            const double t = map_.axis(a).periodic() ? double(idx[a]) / n[a] : double(idx[a]) / (n[a] - 1);
            uvw[a] = map_.lo()[a] + map_.range()[a] * t;
          }
          sampleUvw_.push_back(uvw);
          sampleX_.push_back(map_.evaluate(uvw, J));
        }
  }

  RestMap map_;
  const Lattice& lattice_;
  EmbedOptions options_;
  Eigen::Vector3d restMin_, restMax_;  // bounding box of the rest points (local)
  double tol_;
  Eigen::Matrix3d affineInverse_;
  std::optional<CylinderRestShape> cylinder_;
  std::optional<CylinderStart> cylinderStart_;  // untouched cylinders with a cubic angular axis
  Eigen::Matrix3d curvature_ = Eigen::Matrix3d::Zero();  // cubic only, see certified()
  std::vector<Eigen::Vector3d> sampleUvw_;
  std::vector<Eigen::Vector3d> sampleX_;
  bool wantsInverseGrid_ = false;
  InverseGrid grid_;
};

}  // namespace ffdkit::ffd::detail
