#include "ffdkit/ffd/shape_constraints.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "cell_polynomials.h"
#include "closed_surface_moments.h"
#include "minimum_norm.h"
#include "point_window.h"
#include "vector_clones.h"
#include "volume_polynomial.h"

namespace ffdkit::ffd {
namespace {

constexpr Eigen::Index kParallelPoints = 16384;
constexpr int kBatch = 16;       // points whose window weights and gradients are staged at once
constexpr int kMaxColumns = 12;  // a per-vertex volume's gradient and a centroid's three

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The 64 window weights of `count` points of one cell for axes of degree <= 3: basis[i][4 c + b],
// lane a, is s_i Nu_a(u_i) Nv_b(v_i) Nw_c(w_i) (zero beyond the degree; the basis from the cells'
// power form, CellPolynomials). s: the blend weights, or null for 1.
FFDKIT_VECTOR_CLONES
void cubicWindowBatch(const detail::CellPolynomials poly[3], const std::array<int, 3>& cell, const double* u,
                      const double* v, const double* w, const double* s, int count, detail::Lane4 (*basis)[16]) {
  for (int i = 0; i < count; ++i) {
    detail::Lane4 Nu, Nv, Nw, D;
    poly[0].evaluate(cell[0], u[i], Nu, D);
    poly[1].evaluate(cell[1], v[i], Nv, D);
    poly[2].evaluate(cell[2], w[i], Nw, D);
    if (s != nullptr) Nv *= s[i];
    alignas(32) double vw[4][4];  // vw[c][b] = s Nv_b Nw_c
    for (int c = 0; c < 4; ++c) {
      const detail::Lane4 row = Nv * Nw[c];
      for (int b = 0; b < 4; ++b) vw[c][b] = row[b];
    }
    for (int c = 0; c < 4; ++c)
      for (int b = 0; b < 4; ++b) basis[i][4 * c + b] = vw[c][b] * Nu;
  }
}

// window[k][j] += sum_i basis[i][j] g[columns i + k]: one column at a time over the batch, eight
// accumulators in registers, the gradient's value broadcast from memory (a load, not a shuffle).
FFDKIT_VECTOR_CLONES
void accumulateBatch(const detail::Lane4 (*basis)[16], const double* g, int count, int columns,
                     detail::Lane4 (*window)[16]) {
  for (int k = 0; k < columns; ++k)
    for (int half = 0; half < 16; half += 8) {
      detail::Lane4 acc[8];
      for (int j = 0; j < 8; ++j) acc[j] = window[k][half + j];
      for (int i = 0; i < count; ++i) {
        const double gk = g[columns * i + k];
        for (int j = 0; j < 8; ++j) acc[j] += basis[i][half + j] * gk;
      }
      for (int j = 0; j < 8; ++j) window[k][half + j] = acc[j];
    }
}

// The transpose of the deformation's linear part for `columns` world gradients at once (groups
// of three: x, y, z of one function of the deformed points): for a per-point gradient g, the
// gradient with respect to the LOCAL control points,
//   G_i = F.linear()^T sum_p s_p B_i(u_p, v_p, w_p) g_p   (#controlPoints x columns),
// since x'_p = x_p + F.linear() sum_i s_p B_i (dP_i) (deformer.h). Walks the embedding's blocks
// like Deformer: per block, the cell's window accumulates sum_p s B g over batches of points, then
// scatters; the basis is evaluated once per point whatever the number of columns.
// `gradient(points, count, out)` writes the gradients of `count` points (original indices) into
// out[columns i + k]; it is asked for every point exactly once, in the embedding's order.
template <class Gradient>
RowMajorMatrix adjointDeform(const Lattice& lattice, const Embedding& embedding, int columns, const Gradient& gradient) {
  if (columns < 1 || columns > kMaxColumns) throw std::logic_error("adjointDeform: 1 to 12 columns");
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
  RowMajorMatrix total = RowMajorMatrix::Zero(lattice.pointCount(), columns);
#pragma omp parallel if (n >= kParallelPoints)
  {
    RowMajorMatrix local = RowMajorMatrix::Zero(lattice.pointCount(), columns);
    std::vector<double> bu(static_cast<std::size_t>(np[0])), bv(static_cast<std::size_t>(np[1])),
        bw(static_cast<std::size_t>(np[2]));
    // acc(a + np0 (b + np1 c), k) = sum over the block's points of s bu[a] bv[b] bw[c] g_k.
    RowMajorMatrix acc(window, columns);
    std::vector<double> weights(static_cast<std::size_t>(window));
    std::vector<Eigen::Index> indices(static_cast<std::size_t>(window));
    std::vector<double> g(static_cast<std::size_t>(kBatch * columns));
    alignas(64) detail::Lane4 basis[kBatch][16];
    alignas(64) detail::Lane4 window4[kMaxColumns][16];
    Eigen::Index points[kBatch];
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t t = 0; t < tileCount; ++t) {
      for (std::uint32_t bi = tiles[t]; bi < tiles[t + 1]; ++bi) {
        const Embedding::Block& block = blocks[bi];
        if (block.kind == Embedding::BlockKind::Frozen) continue;
        const std::array<int, 3> cell = embedding.cellOf(block);
        const bool blended = block.kind == Embedding::BlockKind::Blended;
        if (cubic)
          for (int k = 0; k < columns; ++k)
            for (int j = 0; j < 16; ++j) window4[k][j] = detail::Lane4{0, 0, 0, 0};
        else acc.setZero();
        for (std::uint32_t q0 = block.begin; q0 < block.end; q0 += kBatch) {
          const int count = int(std::min<std::uint32_t>(kBatch, block.end - q0));
          for (int i = 0; i < count; ++i) points[i] = order.empty() ? Eigen::Index(q0) + i : order[q0 + i];
          gradient(points, count, g.data());
          const double* s = blended ? embedding.blendWeight().data() + block.blendOffset + (q0 - block.begin) : nullptr;
          if (cubic) {
            cubicWindowBatch(poly, cell, embedding.sortedU().data() + q0, embedding.sortedV().data() + q0,
                             embedding.sortedW().data() + q0, s, count, basis);
            accumulateBatch(basis, g.data(), count, columns, window4);
            continue;
          }
          for (int i = 0; i < count; ++i) {
            const std::uint32_t q = q0 + std::uint32_t(i);
            detail::windowWeights(lattice, cell, embedding.sortedU()[q], embedding.sortedV()[q], embedding.sortedW()[q],
                                  s ? s[i] : 1.0, bu.data(), bv.data(), bw.data(), weights.data());
            const Eigen::Map<const Eigen::RowVectorXd> gp(g.data() + std::ptrdiff_t(columns) * i, columns);
            for (int wi = 0; wi < window; ++wi) acc.row(wi) += weights[std::size_t(wi)] * gp;
          }
        }
        if (cubic)
          for (int c = 0; c < np[2]; ++c)
            for (int b = 0; b < np[1]; ++b)
              for (int a = 0; a < np[0]; ++a)
                for (int k = 0; k < columns; ++k) acc(a + np[0] * (b + np[1] * c), k) = window4[k][4 * c + b][a];
        detail::windowControlIndices(lattice, cell, indices.data());
        for (int wi = 0; wi < window; ++wi) local.row(indices[std::size_t(wi)]) += acc.row(wi);
      }
    }
#pragma omp critical
    total += local;
  }
  // Each group of three columns is a world gradient: rows (L^T G_i^T)^T = G_i L.
  const Eigen::Matrix3d L = lattice.frame().linear();
  for (int k = 0; k + 2 < columns; k += 3) total.middleCols(k, 3) = (total.middleCols(k, 3) * L).eval();
  return total;
}

// Flattened #controlPoints*3 vector (row-major: 3 i + c) of a #controlPoints x 3 matrix.
Eigen::VectorXd flatten(const Eigen::MatrixX3d& m) {
  Eigen::VectorXd out(m.rows() * 3);
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (int c = 0; c < 3; ++c) out[3 * i + c] = m(i, c);
  return out;
}

// Column group [k, k + 3) of a #controlPoints x columns adjoint result, flattened (3 i + c).
Eigen::VectorXd flattenColumns(const RowMajorMatrix& m, int k) {
  Eigen::VectorXd out(m.rows() * 3);
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (int c = 0; c < 3; ++c) out[3 * i + c] = m(i, k + c);
  return out;
}

// The volume and the centroid kept on the same triangles share them: solve() sums both in one
// pass over the triangles.
bool sameSurface(const std::shared_ptr<const ClosedSurface>& kept, const ClosedSurface& surface) {
  return kept && kept->vertexCount() == surface.vertexCount() && kept->triangles() == surface.triangles();
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
  const auto rows = [&g](const Eigen::Index* points, int count, double* out) {
    for (int i = 0; i < count; ++i)
      for (int c = 0; c < 3; ++c) out[3 * i + c] = g(points[i], c);
  };
  return flattenColumns(adjointDeform(lattice_, deformer_.embedding(), 3, rows), 0);
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
  volumeSurface_ = sameSurface(centroidSurface_, surface) ? centroidSurface_ : std::make_shared<ClosedSurface>(surface);
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
  centroidSurface_ = sameSurface(volumeSurface_, surface) ? volumeSurface_ : std::make_shared<ClosedSurface>(surface);
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
  double previousResidual = std::numeric_limits<double>::infinity();  // the largest scaled one, the step before
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
  Eigen::MatrixXd J(m, f);
  for (Eigen::Index r = 0; r < linearCount; ++r)
    for (Eigen::Index k = 0; k < f; ++k) J(r, k) = linearRows_[std::size_t(r)][freeIndex[std::size_t(k)]];
  for (int iteration = 0;; ++iteration) {
    Eigen::MatrixX3d moved = lattice.controlPoints() + result.change;
    current.setControlPoints(moved);
    const Eigen::MatrixX3d displacement = moved - lattice.restPoints();  // local P + dP - Pbar
    if (perVertex) deformer_.deform(current, points_);
    const Eigen::MatrixX3d& x = deformer_.points();
    // Residuals c and their scales; the rows of J only once the residuals ask for another step.
    Eigen::VectorXd c(m), scale(m);
    const Eigen::VectorXd flatDisplacement = flatten(displacement);
    for (Eigen::Index r = 0; r < linearCount; ++r) {
      const std::size_t ri = std::size_t(r);
      const Eigen::VectorXd terms = linearRows_[ri].cwiseProduct(flatDisplacement);
      c[r] = linearRest_[ri] + linearOffset[ri] + terms.sum() - linearB_[ri];
      const double magnitude = linearRestScale_[ri] + terms.cwiseAbs().sum() + std::abs(linearB_[ri]);
      scale[r] = magnitude > 0.0 ? magnitude : 1.0;
    }
    Eigen::Index row = linearCount;
    // Volume and centroid are translation invariant: measured about the object's mean so that
    // the divergence-theorem sums do not lose digits to the distance from the world origin. One
    // pass over the triangles gives both when they are kept on the same surface.
    std::optional<detail::SurfaceSums> volumeSums, centroidSums;
    if (centroidSurface_) centroidSums = detail::surfaceSums(x, origin_, *centroidSurface_, centroidTarget_);
    if (volumeSurface_ && !polynomial)
      volumeSums = centroidSurface_ == volumeSurface_ ? centroidSums
                                                      : detail::surfaceSums(x, origin_, *volumeSurface_, centroidTarget_);
    Eigen::MatrixX3d polynomialGradient;  // world dV/dD, with the volume polynomial
    if (volumeSurface_) {
      const double volume = polynomial ? volumePolynomial_->evaluate(displacement * L.transpose(), polynomialGradient)
                                       : volumeSums->volume;
      c[row] = volume - volumeTarget_;
      scale[row] = std::abs(volumeTarget_);
      result.volume = volume;
      result.volumeRelativeError = std::abs(c[row]) / scale[row];
      ++row;
    }
    if (centroidSurface_) {
      // Scale: the volume times the surface's size (the units of M - t V).
      const double centroidScale =
          std::max(std::abs(centroidSums->volume), 1e-300) * (size + (centroidTarget_ - origin_).norm());
      for (int k = 0; k < 3; ++k, ++row) {
        c[row] = centroidSums->centroidResidual[k];
        scale[row] = centroidScale;
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
    // The rows of J over the free coordinates: a linear row's is constant (filled before the
    // loop), the polynomial volume's comes with its value, the per-vertex rows from one adjoint
    // pass (the volume's gradient in columns 0-2, the centroid's three in the next nine).
    row = linearCount;
    if (volumeSurface_ && polynomial) {
      const Eigen::VectorXd gradient = flatten(polynomialGradient * L);  // local: L^T dV/dD
      for (Eigen::Index k = 0; k < f; ++k) J(row, k) = gradient[freeIndex[std::size_t(k)]];
      ++row;
    }
    // JacobianUpdate::FirstStep keeps the per-vertex rows while each step cuts the residual
    // tenfold (a chord method); a step that does not, and every step of EveryStep, computes them.
    const bool rowsDue = options.jacobian == JacobianUpdate::EveryStep || result.jacobianPasses == 0 ||
                         result.largestRelativeResidual > 0.1 * previousResidual;
    previousResidual = result.largestRelativeResidual;
    if (perVertex && rowsDue) {
      ++result.jacobianPasses;
      const bool volumeColumns = volumeSurface_ && !polynomial;
      const int columns = (volumeColumns ? 3 : 0) + (centroidSurface_ ? 9 : 0);
      const detail::SurfaceGradients surfaceGradients(x, origin_, centroidTarget_);
      const auto gradients = [&](const Eigen::Index* points, int count, double* out) {
        if (volumeColumns) surfaceGradients.volume(*volumeSurface_, points, count, out, columns);
        if (centroidSurface_)
          surfaceGradients.centroid(*centroidSurface_, points, count, out + (volumeColumns ? 3 : 0), columns);
      };
      const RowMajorMatrix G = adjointDeform(lattice_, deformer_.embedding(), columns, gradients);
      for (int k = 0; k < columns; k += 3, ++row) {
        const Eigen::VectorXd gradient = flattenColumns(G, k);
        for (Eigen::Index j = 0; j < f; ++j) J(row, j) = gradient[freeIndex[std::size_t(j)]];
      }
    }
    // Minimum-norm Newton step: delta_new = J^T (J J^T)^+ (J delta - c).
    const Eigen::VectorXd rhs = J * delta - c;
    const Eigen::MatrixXd gram = J * J.transpose();
    const Eigen::VectorXd y = detail::minimumNormSolve(gram, rhs);
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
