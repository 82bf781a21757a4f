#include "ffdkit/ffd/shape_constraints.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/QR>

#include "cell_polynomials.h"
#include "point_window.h"
#include "vector_clones.h"
#include "volume_polynomial.h"

namespace ffdkit::ffd {
namespace {

constexpr Eigen::Index kParallelPoints = 16384;

// One block of adjointDeform for axes of degree <= 3: the basis from the cells' power form
// (CellPolynomials, four lanes, zero beyond the degree) and the window accumulated four
// u-functions at a time, acc[k][c][b] (lane a) for coordinate k. One coordinate per pass keeps its
// sixteen accumulators in vector registers; compiled for AVX2 / AVX-512 too (Lane4 is one register).
FFDKIT_VECTOR_CLONES
void adjointBlockCubic(const Embedding& embedding, const Embedding::Block& block, const std::array<int, 3>& cell,
                       const detail::CellPolynomials poly[3], const Eigen::Ref<const Eigen::MatrixX3d>& g,
                       detail::Lane4 acc[3][4][4]) {
  const auto& order = embedding.order();
  for (int k = 0; k < 3; ++k) {
    detail::Lane4 sum[4][4];
    for (int c = 0; c < 4; ++c)
      for (int b = 0; b < 4; ++b) sum[c][b] = detail::Lane4{0, 0, 0, 0};
    for (std::uint32_t q = block.begin; q < block.end; ++q) {
      const Eigen::Index p = order.empty() ? q : order[q];
      const double s = block.kind == Embedding::BlockKind::Blended
                           ? embedding.blendWeight()[block.blendOffset + q - block.begin]
                           : 1.0;
      detail::Lane4 Nu, Nv, Nw, D;
      poly[0].evaluate(cell[0], embedding.sortedU()[q], Nu, D);
      poly[1].evaluate(cell[1], embedding.sortedV()[q], Nv, D);
      poly[2].evaluate(cell[2], embedding.sortedW()[q], Nw, D);
      const double sg = s * g(p, k);
      for (int c = 0; c < 4; ++c) {
        const detail::Lane4 t = (sg * Nw[c]) * Nv;
        for (int b = 0; b < 4; ++b) sum[c][b] += t[b] * Nu;
      }
    }
    for (int c = 0; c < 4; ++c)
      for (int b = 0; b < 4; ++b) acc[k][c][b] = sum[c][b];
  }
}

// The transpose of the deformation's linear part: for a world gradient g (#points x 3) of some
// function of the deformed points, its gradient with respect to the LOCAL control points,
//   G_i = F.linear()^T sum_p s_p B_i(u_p, v_p, w_p) g_p   (#controlPoints x 3),
// since x'_p = x_p + F.linear() sum_i s_p B_i (dP_i) (deformer.h). Walks the embedding's blocks
// like Deformer: per block, the cell's window accumulates sum_p s B g, then scatters.
Eigen::MatrixX3d adjointDeform(const Lattice& lattice, const Embedding& embedding,
                               const Eigen::Ref<const Eigen::MatrixX3d>& g) {
  const Eigen::Index n = embedding.pointCount();
  int np[3];
  bool cubic = true;
  for (int a = 0; a < 3; ++a) {
    np[a] = lattice.axis(a).degree() + 1;
    cubic = cubic && detail::CellPolynomials::supports(lattice.axis(a));
  }
  // The cubic kernel sums the polynomial basis B; a rational lattice's coefficients are R = w B / sum w B.
  cubic = cubic && !lattice.isRational();
  detail::CellPolynomials poly[3];
  if (cubic)
    for (int a = 0; a < 3; ++a) poly[a] = detail::CellPolynomials(lattice.axis(a));
  const int window = np[0] * np[1] * np[2];
  const auto& blocks = embedding.blocks();
  const auto& tiles = embedding.tileBlocks();
  const auto& order = embedding.order();
  const std::int64_t tileCount = static_cast<std::int64_t>(tiles.size()) - 1;
  Eigen::MatrixX3d total = Eigen::MatrixX3d::Zero(lattice.pointCount(), 3);
#pragma omp parallel if (n >= kParallelPoints)
  {
    Eigen::MatrixX3d local = Eigen::MatrixX3d::Zero(lattice.pointCount(), 3);
    std::vector<double> bu(static_cast<std::size_t>(np[0])), bv(static_cast<std::size_t>(np[1])),
        bw(static_cast<std::size_t>(np[2]));
    // acc(a + np0 (b + np1 c), :) = sum over the block's points of s bu[a] bv[b] bw[c] g.
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> acc(window, 3);
    std::vector<double> weights(static_cast<std::size_t>(window));
    std::vector<Eigen::Index> indices(static_cast<std::size_t>(window));
    alignas(32) detail::Lane4 acc4[3][4][4];
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t t = 0; t < tileCount; ++t) {
      for (std::uint32_t bi = tiles[t]; bi < tiles[t + 1]; ++bi) {
        const Embedding::Block& block = blocks[bi];
        if (block.kind == Embedding::BlockKind::Frozen) continue;
        const std::array<int, 3> cell = embedding.cellOf(block);
        if (cubic) {
          adjointBlockCubic(embedding, block, cell, poly, g, acc4);
          for (int c = 0; c < np[2]; ++c)
            for (int b = 0; b < np[1]; ++b)
              for (int a = 0; a < np[0]; ++a)
                acc.row(a + np[0] * (b + np[1] * c)) << acc4[0][c][b][a], acc4[1][c][b][a], acc4[2][c][b][a];
        } else {
          acc.setZero();
          for (std::uint32_t q = block.begin; q < block.end; ++q) {
            const Eigen::Index p = order.empty() ? q : order[q];
            const double s = block.kind == Embedding::BlockKind::Blended
                                 ? embedding.blendWeight()[block.blendOffset + q - block.begin]
                                 : 1.0;
            detail::windowWeights(lattice, cell, embedding.sortedU()[q], embedding.sortedV()[q], embedding.sortedW()[q],
                                  s, bu.data(), bv.data(), bw.data(), weights.data());
            const Eigen::RowVector3d gp = g.row(p);
            for (int wi = 0; wi < window; ++wi) acc.row(wi) += weights[std::size_t(wi)] * gp;
          }
        }
        detail::windowControlIndices(lattice, cell, indices.data());
        for (int wi = 0; wi < window; ++wi) local.row(indices[std::size_t(wi)]) += acc.row(wi);
      }
    }
#pragma omp critical
    total += local;
  }
  return total * lattice.frame().linear();  // rows: (L^T G_i^T)^T = G_i L
}

// Flattened #controlPoints*3 vector (row-major: 3 i + c) of a #controlPoints x 3 matrix.
Eigen::VectorXd flatten(const Eigen::MatrixX3d& m) {
  Eigen::VectorXd out(m.rows() * 3);
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (int c = 0; c < 3; ++c) out[3 * i + c] = m(i, c);
  return out;
}

// Per-vertex volume gradient sum (y_b x y_c) / 6 over the triangles (v, b, c) at v, y = x - origin
// (the volume does not depend on the origin; measuring about the object keeps digits), into g
// (#points x 3, reused between steps: no fresh pages per step); `volume` gets
// sum_v y_v . gradient_v / 3 (each triangle's determinant counted three times).
void volumeGradient(const Eigen::MatrixX3d& x, const Eigen::Vector3d& origin, const ClosedSurface& surface,
                    double& volume, Eigen::MatrixX3d& g) {
  const Eigen::Index n = x.rows();
  g.resize(n, 3);
  const auto& offsets = surface.pairOffsets();
  const auto& pairs = surface.pairs();
  const Eigen::RowVector3d o = origin.transpose();
  double sum = 0.0;
#pragma omp parallel for reduction(+ : sum) schedule(static) if (n >= kParallelPoints)
  for (Eigen::Index v = 0; v < n; ++v) {
    Eigen::Vector3d acc = Eigen::Vector3d::Zero();
    for (int e = offsets[v]; e < offsets[v + 1]; ++e)
      acc += (x.row(pairs(e, 0)) - o).transpose().cross((x.row(pairs(e, 1)) - o).transpose());
    acc /= 6.0;
    g.row(v) = acc.transpose();
    sum += (x.row(v) - o).dot(acc.transpose());
  }
  volume = sum / 3.0;
}

// The centroid's residual M - t V (3 values; M = sum det (a + b + c) / 24, V = sum det / 6) and
// its per-vertex gradients, one #points x 3 matrix per component.
void centroidResidual(const Eigen::MatrixX3d& x, const ClosedSurface& surface, const Eigen::Vector3d& target,
                      Eigen::Vector3d& residual, Eigen::MatrixX3d gradient[3]) {
  const Eigen::Index n = x.rows();
  for (int k = 0; k < 3; ++k) gradient[k].setZero(n, 3);
  const auto& offsets = surface.pairOffsets();
  const auto& pairs = surface.pairs();
  double r0 = 0.0, r1 = 0.0, r2 = 0.0;
#pragma omp parallel for reduction(+ : r0, r1, r2) schedule(static) if (n >= kParallelPoints)
  for (Eigen::Index v = 0; v < n; ++v) {
    const Eigen::Vector3d a = x.row(v).transpose();
    Eigen::Matrix3d grad = Eigen::Matrix3d::Zero();  // column k: gradient of component k at v
    Eigen::Vector3d value = Eigen::Vector3d::Zero();
    for (int e = offsets[v]; e < offsets[v + 1]; ++e) {
      const Eigen::Vector3d b = x.row(pairs(e, 0)).transpose(), c = x.row(pairs(e, 1)).transpose();
      const Eigen::Vector3d bc = b.cross(c);
      const double det = a.dot(bc);
      const Eigen::Vector3d sum = a + b + c;
      // d/da [det (a+b+c)_k / 24 - t_k det / 6] = bc ((a+b+c)_k / 24 - t_k / 6) + det e_k / 24.
      for (int k = 0; k < 3; ++k) {
        grad.col(k) += bc * (sum[k] / 24.0 - target[k] / 6.0);
        grad(k, k) += det / 24.0;
      }
      value += det * (sum / 24.0 - target / 6.0);  // each triangle seen from its 3 vertices
    }
    for (int k = 0; k < 3; ++k) gradient[k].row(v) = grad.col(k).transpose();
    r0 += value[0];
    r1 += value[1];
    r2 += value[2];
  }
  residual = Eigen::Vector3d(r0, r1, r2) / 3.0;
}

void checkSurface(const ClosedSurface& surface, Eigen::Index points, const char* what) {
  if (surface.vertexCount() != points)
    throw ConstraintError(std::string(what) + ": the surface has " + std::to_string(surface.vertexCount()) +
                          " vertices, the constrained object " + std::to_string(points) + " points");
}

}  // namespace

ShapeConstraints::ShapeConstraints(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& points,
                                   const EmbedOptions& embedOptions)
    : lattice_(lattice), rowWeights_(lattice.weights()), points_(points), deformer_(embed(lattice, points, embedOptions)) {
  free_.setConstant(lattice.pointCount(), 3, true);
  if (points_.rows() > 0) origin_ = points_.colwise().mean().transpose();
}

void ShapeConstraints::setFreeControls(const ControlMask& free) {
  if (free.rows() != free_.rows())
    throw ConstraintError("setFreeControls: mask has " + std::to_string(free.rows()) + " rows, the lattice " +
                          std::to_string(free_.rows()) + " control points");
  free_ = free;
}

void ShapeConstraints::addLinear(const Eigen::SparseMatrix<double, Eigen::RowMajor>& A,
                                 const Eigen::Ref<const Eigen::VectorXd>& b) {
  const Eigen::Index n = points_.rows();
  if (A.cols() != 3 * n)
    throw ConstraintError("addLinear: A has " + std::to_string(A.cols()) + " columns, expected 3 x " +
                          std::to_string(n) + " points = " + std::to_string(3 * n));
  if (A.rows() != b.size())
    throw ConstraintError("addLinear: A has " + std::to_string(A.rows()) + " rows but b " + std::to_string(b.size()) +
                          " values");
  if (!b.allFinite()) throw ConstraintError("addLinear: b must be finite");
  for (Eigen::Index r = 0; r < A.outerSize(); ++r)
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, r); it; ++it)
      if (!std::isfinite(it.value()))
        throw ConstraintError("addLinear: A(" + std::to_string(r) + ", " + std::to_string(it.col()) + ") is not finite");
  for (Eigen::Index r = 0; r < A.outerSize(); ++r) {
    linearA_.push_back(A.row(r));
    linearRows_.push_back(rowOf(linearA_.back()));
    linearB_.push_back(b[r]);
    double rest = 0.0, magnitude = 0.0;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, r); it; ++it) {
      const double term = it.value() * points_(it.col() / 3, it.col() % 3);
      rest += term;
      magnitude += std::abs(term);
    }
    linearRest_.push_back(rest);
    linearRestScale_.push_back(magnitude);
  }
}

Eigen::VectorXd ShapeConstraints::rowOf(const Eigen::SparseVector<double>& a) const {
  Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(points_.rows(), 3);
  for (Eigen::SparseVector<double>::InnerIterator it(a); it; ++it) g(it.index() / 3, it.index() % 3) += it.value();
  // Rows J = A d x'/d dP: the adjoint of the deformation applied to the row (constant while the
  // weights are).
  return flatten(adjointDeform(lattice_, deformer_.embedding(), g));
}

void ShapeConstraints::adoptWeights(const Lattice& lattice) {
  const Eigen::VectorXd weights = lattice.weights();
  if (weights == rowWeights_) return;
  lattice_.setWeights(weights);
  rowWeights_ = weights;
  for (std::size_t r = 0; r < linearRows_.size(); ++r) linearRows_[r] = rowOf(linearA_[r]);
}

bool ShapeConstraints::polynomialApplies(const Lattice& lattice, const char* what) const {
  if (!volumePolynomial_) return false;
  if (!lattice.isRational()) return true;
  const Eigen::VectorXd weights = lattice.weights(), rest = lattice.restWeights();
  if (weights == rest) return true;
  if (volumeEvaluation_ == VolumeEvaluation::Polynomial) {
    Eigen::Index i = 0;
    (weights - rest).cwiseAbs().maxCoeff(&i);
    throw LatticeError(std::string(what) + ": the volume polynomial (VolumeEvaluation::Polynomial) holds while the "
                       "weights equal the rest weights; control point " + std::to_string(i) + " has weight " +
                       std::to_string(weights[i]) + ", rest weight " + std::to_string(rest[i]) +
                       " (keep the volume with Automatic or PerVertex to follow weight edits)");
  }
  return false;
}

void ShapeConstraints::keepBarycentre(const Eigen::Vector3d& target) {
  if (!target.allFinite()) throw ConstraintError("keepBarycentre: target must be finite");
  const Eigen::Index n = points_.rows();
  if (n == 0) throw ConstraintError("keepBarycentre: no points");
  Eigen::SparseMatrix<double, Eigen::RowMajor> A(3, 3 * n);
  A.reserve(Eigen::VectorXi::Constant(3, int(n)));
  for (int c = 0; c < 3; ++c)
    for (Eigen::Index p = 0; p < n; ++p) A.insert(c, 3 * p + c) = 1.0 / double(n);
  addLinear(A, target);
}

void ShapeConstraints::keepVolume(const ClosedSurface& surface, double target, VolumeEvaluation evaluation) {
  checkSurface(surface, points_.rows(), "keepVolume");
  if (!std::isfinite(target) || target == 0.0)
    throw ConstraintError("keepVolume: the target volume must be finite and non-zero, got " + std::to_string(target));
  volumeSurface_ = std::make_shared<ClosedSurface>(surface);
  volumeTarget_ = target;
  volumeEvaluation_ = evaluation;
  volumePolynomial_.reset();
  if (evaluation == VolumeEvaluation::PerVertex) return;
  // The polynomial is built in the displacements P - Pbar, which are the whole map only when the
  // weights equal the rest weights (see solve()); otherwise the volume is summed per vertex.
  if (lattice_.weights() != lattice_.restWeights()) {
    if (evaluation == VolumeEvaluation::Polynomial)
      throw ConstraintError("keepVolume: the volume polynomial needs the lattice's weights equal to its rest weights; "
                            "use VolumeEvaluation::PerVertex");
    return;
  }
  std::optional<detail::VolumePolynomial> polynomial =
      detail::VolumePolynomial::build(lattice_, deformer_.embedding(), points_, origin_, *volumeSurface_);
  if (polynomial) {
    volumePolynomial_ = std::make_shared<const detail::VolumePolynomial>(std::move(*polynomial));
  } else if (evaluation == VolumeEvaluation::Polynomial) {
    throw ConstraintError("keepVolume: the volume polynomial needs at most " +
                          std::to_string(detail::VolumePolynomial::kMaxActiveControls) +
                          " control points moving the surface; use VolumeEvaluation::PerVertex");
  }
}

double ShapeConstraints::keptVolume(const Lattice& lattice) const {
  if (!volumeSurface_) throw ConstraintError("keptVolume: no volume is kept (keepVolume)");
  deformer_.embedding().checkLattice(lattice);
  if (polynomialApplies(lattice, "keptVolume")) {
    Eigen::MatrixX3d gradient;
    const Eigen::MatrixX3d world = (lattice.controlPoints() - lattice.restPoints()) * lattice_.frame().linear().transpose();
    return volumePolynomial_->evaluate(world, gradient);
  }
  deformer_.deform(lattice, points_);
  deformedStale_ = true;
  return enclosedVolume(deformer_.points(), *volumeSurface_);
}

const Eigen::MatrixX3d& ShapeConstraints::deformedPoints() const {
  if (!solved_) throw ConstraintError("deformedPoints: no solve() yet");
  if (deformedStale_) {
    deformer_.deform(*solved_, points_);
    deformedStale_ = false;
  }
  return deformer_.points();
}

void ShapeConstraints::keepCentroid(const ClosedSurface& surface, const Eigen::Vector3d& target) {
  checkSurface(surface, points_.rows(), "keepCentroid");
  if (!target.allFinite()) throw ConstraintError("keepCentroid: target must be finite");
  centroidSurface_ = std::make_shared<ClosedSurface>(surface);
  centroidTarget_ = target;
}

ShapeSolveResult ShapeConstraints::solve(const Lattice& lattice, const ShapeSolveOptions& options) {
  deformer_.embedding().checkLattice(lattice);
  // Rows built for other weights are rebuilt; the volume polynomial holds at the rest weights only.
  const bool polynomial = polynomialApplies(lattice, "ShapeConstraints::solve");
  adoptWeights(lattice);
  const Eigen::Index controls = lattice.pointCount();
  // The free coordinates, in flattened order 3 i + c.
  std::vector<Eigen::Index> freeIndex;
  for (Eigen::Index i = 0; i < controls; ++i)
    for (int c = 0; c < 3; ++c)
      if (free_(i, c)) freeIndex.push_back(3 * i + c);
  const Eigen::Index f = Eigen::Index(freeIndex.size());
  const Eigen::Index linearCount = Eigen::Index(linearRows_.size());
  const Eigen::Index m = linearCount + (volumeSurface_ ? 1 : 0) + (centroidSurface_ ? 3 : 0);

  ShapeSolveResult result;
  result.change.setZero(controls, 3);
  Eigen::VectorXd delta = Eigen::VectorXd::Zero(f);  // the free part of the change
  Lattice current = lattice;
  const double size = lattice.restSize();
  // With the volume polynomial and no centroid, no step visits the points.
  const bool perVertex = (volumeSurface_ && !polynomial) || centroidSurface_;
  double lastStepNorm = std::numeric_limits<double>::infinity();
  const Eigen::Matrix3d L = lattice_.frame().linear();
  // Weights that differ from the rest weights (Lamousin & Waggenspack 1994) make the map
  // x' = Q + s F (sum R P - Xbar) with sum R Pbar != Xbar: a linear row's a . x' then holds the
  // constant a . s F (sum R Pbar - Xbar), measured once from the deformed points of `lattice`.
  std::vector<double> linearOffset(std::size_t(linearCount), 0.0);
  if (linearCount > 0 && lattice.weights() != lattice.restWeights()) {
    const Eigen::MatrixX3d& start = deformer_.deform(lattice, points_);
    deformedStale_ = true;
    const Eigen::VectorXd flatStart = flatten(Eigen::MatrixX3d(lattice.controlPoints() - lattice.restPoints()));
    for (Eigen::Index r = 0; r < linearCount; ++r) {
      const std::size_t ri = std::size_t(r);
      double value = 0.0;
      for (Eigen::SparseVector<double>::InnerIterator it(linearA_[ri]); it; ++it)
        value += it.value() * start(it.index() / 3, it.index() % 3);
      linearOffset[ri] = value - linearRest_[ri] - linearRows_[ri].dot(flatStart);
    }
  }
  for (int iteration = 0;; ++iteration) {
    Eigen::MatrixX3d moved = lattice.controlPoints() + result.change;
    current.setControlPoints(moved);
    const Eigen::MatrixX3d displacement = moved - lattice.restPoints();  // local P + dP - Pbar
    // Volume and centroid are translation invariant: measured about the object's mean so that
    // the divergence-theorem sums do not lose digits to the distance from the world origin.
    if (perVertex) deformer_.deform(current, points_);
    const Eigen::MatrixX3d& x = deformer_.points();
    Eigen::MatrixX3d centred;
    if (centroidSurface_) centred = x.rowwise() - origin_.transpose();
    // Residuals c, their scales and the rows of J over the free coordinates. A linear row is
    // a . x' = a . x + J (P + dP - Pbar) (its J is the adjoint of the deformation, constant).
    Eigen::VectorXd c(m), scale(m);
    Eigen::MatrixXd J(m, f);
    const Eigen::VectorXd flatDisplacement = flatten(displacement);
    for (Eigen::Index r = 0; r < linearCount; ++r) {
      const std::size_t ri = std::size_t(r);
      const Eigen::VectorXd terms = linearRows_[ri].cwiseProduct(flatDisplacement);
      c[r] = linearRest_[ri] + linearOffset[ri] + terms.sum() - linearB_[ri];
      const double magnitude = linearRestScale_[ri] + terms.cwiseAbs().sum() + std::abs(linearB_[ri]);
      scale[r] = magnitude > 0.0 ? magnitude : 1.0;
      for (Eigen::Index k = 0; k < f; ++k) J(r, k) = linearRows_[ri][freeIndex[std::size_t(k)]];
    }
    Eigen::Index row = linearCount;
    if (volumeSurface_) {
      double volume = 0.0;
      Eigen::VectorXd gradient;
      if (polynomial) {
        // World displacements D_i = L dP_i (rows: dP L^T); the local gradient is L^T dV/dD.
        Eigen::MatrixX3d worldGradient;
        volume = volumePolynomial_->evaluate(displacement * L.transpose(), worldGradient);
        gradient = flatten(worldGradient * L);
      } else {
        Eigen::MatrixX3d& g = gradientScratch_;
        volumeGradient(x, origin_, *volumeSurface_, volume, g);
        gradient = flatten(adjointDeform(lattice_, deformer_.embedding(), g));
      }
      c[row] = volume - volumeTarget_;
      scale[row] = std::abs(volumeTarget_);
      for (Eigen::Index k = 0; k < f; ++k) J(row, k) = gradient[freeIndex[std::size_t(k)]];
      result.volume = volume;
      result.volumeRelativeError = std::abs(c[row]) / scale[row];
      ++row;
    }
    if (centroidSurface_) {
      Eigen::Vector3d residual;
      Eigen::MatrixX3d g[3];
      centroidResidual(centred, *centroidSurface_, centroidTarget_ - origin_, residual, g);
      // Scale: the volume times the surface's size (the units of M - t V).
      double volume = 0.0;
      volumeGradient(x, origin_, *centroidSurface_, volume, gradientScratch_);
      for (int k = 0; k < 3; ++k) {
        const Eigen::VectorXd gradient = flatten(adjointDeform(lattice_, deformer_.embedding(), g[k]));
        c[row] = residual[k];
        scale[row] = std::max(std::abs(volume), 1e-300) * (size + (centroidTarget_ - origin_).norm());
        for (Eigen::Index j = 0; j < f; ++j) J(row, j) = gradient[freeIndex[std::size_t(j)]];
        ++row;
      }
    }
    result.largestRelativeResidual = m > 0 ? (c.array().abs() / scale.array()).maxCoeff() : 0.0;
    if (!std::isfinite(result.largestRelativeResidual))
      throw ConstraintError("shape constraints: the residual is not finite after " + std::to_string(iteration) +
                            " Newton steps (the deformation degenerated)");
    const bool nonlinear = volumeSurface_ || centroidSurface_;
    // A step at the rounding level of the control coordinates (1000 eps times the lattice's size)
    // is stationary too: a drag that barely changes the volume asks for a change so small that its
    // relative step cannot fall below `stationarity`.
    const bool roundingStep = lastStepNorm <= 1e3 * std::numeric_limits<double>::epsilon() * size;
    if (result.largestRelativeResidual <= options.tolerance &&
        (!nonlinear || iteration == 0 || result.lastStep <= options.stationarity || roundingStep)) {
      result.iterations = iteration;
      solved_ = current;
      deformedStale_ = true;
      return result;
    }
    if (iteration >= options.maxIterations)
      throw ConstraintError("shape constraints not met after " + std::to_string(iteration) +
                            " Newton steps: largest relative residual " + std::to_string(result.largestRelativeResidual) +
                            (volumeSurface_ ? ", volume relative error " + std::to_string(result.volumeRelativeError) : ""));
    // Minimum-norm Newton step: delta_new = J^T (J J^T)^+ (J delta - c).
    const Eigen::VectorXd rhs = J * delta - c;
    const Eigen::MatrixXd gram = J * J.transpose();
    const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(gram);
    const Eigen::VectorXd y = cod.solve(rhs);
    // Inconsistent rows (no free control moves a constrained quantity, or rows that contradict
    // each other) leave a residual the pseudo-inverse cannot remove.
    const double miss = (gram * y - rhs).norm();
    if (!(miss <= 1e-9 * (rhs.norm() + c.norm()) + 1e-300)) {
      Eigen::Index worst = 0;
      ((gram * y - rhs).array().abs()).maxCoeff(&worst);
      const std::string which = worst < linearCount ? "linear constraint " + std::to_string(worst)
                                : (volumeSurface_ && worst == linearCount) ? "the volume"
                                                                          : "the centroid";
      throw ConstraintError("shape constraints cannot be met with the free control points: " + which +
                            " is not reachable (the constraints contradict each other or no free control changes it)");
    }
    const Eigen::VectorXd next = J.transpose() * y;
    lastStepNorm = (next - delta).norm();
    result.lastStep = lastStepNorm / std::max(next.norm(), 1e-300);
    delta = next;
    result.change.setZero();
    for (Eigen::Index k = 0; k < f; ++k) {
      const Eigen::Index at = freeIndex[std::size_t(k)];
      result.change(at / 3, at % 3) = delta[k];
    }
  }
}

}  // namespace ffdkit::ffd
