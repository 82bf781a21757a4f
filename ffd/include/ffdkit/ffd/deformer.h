#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/ffd/embedding.h"
#include "ffdkit/ffd/lattice.h"

namespace ffdkit::ffd {

/// What the last Deformer call did (for tests, benchmarks and the GUI's status line).
struct DeformStats {
  bool full = false;                 ///< true: deform(); false: update()
  Eigen::Index changedControlPoints = 0;  ///< update(): control points that moved since the last call
  Eigen::Index evaluatedPoints = 0;  ///< points whose output was recomputed
  /// update(lattice): the step moved the same one control point as the step before it and read
  /// that control point's weights at the points, kept by that step, instead of evaluating the
  /// basis (the same bits; 8 bytes per point kept while the deformer lives).
  bool weightsReused = false;
};

/// The arithmetic of the deformation's power-form kernels (lattices whose axes all have degree
/// <= 3: B-splines up to cubic, Bernstein up to 4 points per axis; other lattices, the
/// incremental delta terms and the addition out = Q + s d are always double).
enum class Precision {
  /// Double: agrees with Lattice::evaluate to ~1e-15 relative.
  Double,
  /// The displacement in float32 (sixteen lanes per AVX-512 instruction instead of eight), as
  /// Blender's lattice modifier computes: its error scales with the displacement, not with the
  /// coordinates (at most 1.2e-7 of the largest control-point displacement measured; the tests
  /// hold it to 1e-6). For points that end in float32 anyway (binary PLY, STL, glTF, the
  /// renderer). Faster where the kernel is bound by multiply-adds (1M points, 4x4x4 cubic:
  /// 2.4 ms against 3.7 ms). Blocks of fewer than 64 points of a cell in a tile (many-cell
  /// lattices in random point order) keep the double kernel, which was faster there
  /// (docs/ffd-engine.md); the choice is fixed per block, so exact updates stay bit-identical.
  Single
};

/// The per-frame half of FFD (the mapping of Kuriyama 1996, sec. 6.3.2, eq. (6.1)): given an
/// Embedding, maps the embedded points through the lattice's current control points.
///
/// Each output point is written as  out = Q + s * F.linear() * sum_ijk B_i(u) B_j(v) B_k(w) (P_ijk - Pbar_ijk)
/// with Q the input point (world), F the lattice frame, s = 1 inside (the blend weight of
/// ClampEdge / Falloff outside points, 0 for points left unchanged). Because the basis is a
/// partition of unity and Xbar(u,v,w) = Q, this equals F * X(u,v,w) (eq. (6.1)) for inside
/// points to the embedding tolerance, and it is also the natural approximation when a pipeline
/// stage's input moved but its re-embedding is throttled.
///
/// Rational lattices (Lattice::isRational(), Lamousin & Waggenspack 1994) use the same formula with
/// X and Xbar the ratios sum B w P / sum B w: out = Q + s * F.linear() * (X(u,v,w) - Xbar(u,v,w)).
/// They are evaluated in homogeneous form: the power-form kernels run on the numerator
/// N = sum B w P and the denominator D = sum B w, then divide once per point. The deformer keeps
/// D per point (8 bytes per point, allocated on the first rational call), so that update(lattice)
/// after control points moved with their weights kept adds B_ijk w_ijk dP_ijk / D (the
/// numerator's change over the unchanged denominator); a weight change re-evaluates the cells it
/// touched against the last control points and weights. Polynomial lattices (every weight 1)
/// never touch that state and run the power-form kernels as before.
///
/// Threads: OpenMP over blocks of points that share a lattice cell.
class Deformer {
 public:
  Deformer() = default;
  /// A deformer for the points of `embedding` (taken over; no output until deform()).
  explicit Deformer(Embedding embedding);

  /// The embedding the deformer evaluates.
  const Embedding& embedding() const { return embedding_; }

  /// Full evaluation of every point.
  /// @param lattice the lattice the embedding was built for (same restRevision).
  /// @param input   #points x 3 WORLD points, the ones that were embedded (or a pipeline stage's
  ///                new input when its re-embedding is throttled).
  /// @return #points x 3 deformed WORLD points (a reference to points()).
  /// @throws LatticeError if the embedding is stale for `lattice` or input has the wrong size.
  const Eigen::MatrixX3d& deform(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& input);

  /// Full evaluation with an embedding whose rest lattice has moved since (lattice.restRevision()
  /// differs; the counts must match): out = input + s * F.linear() * sum B (P - Pbar) with the old
  /// (u,v,w). This is the throttled-re-embedding approximation of Kuriyama 1996, sec. 6.3.2, used
  /// by Pipeline for lattices other than the one being edited; exact when the embedding is fresh.
  /// @throws LatticeError if the lattice counts differ from the embedding's or input has the wrong size.
  const Eigen::MatrixX3d& deformStale(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& input);

  /// Incremental evaluation, exact: only the points of lattice cells whose window holds a control
  /// point that changed since the last deform()/update() are re-evaluated, from `input` (the same
  /// points as in deform()). Bit-identical to deform() and free of drift however many updates run.
  /// @throws LatticeError if the embedding is stale, input has the wrong size, or deform() was never called.
  const Eigen::MatrixX3d& update(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& input);

  /// Incremental evaluation without the input points: adds B_ijk(u,v,w) * dP for each control point
  /// that changed since the last call (one multiply-add per influenced point per changed control
  /// point; the dense window of changes when most of a cell's control points moved). Agrees with
  /// deform() to ~1e-16 relative per call, but rounding accumulates over many calls (~1e-12 after
  /// 10^4 updates): call deform() or update(lattice, input) now and then to resynchronise.
  /// @throws LatticeError if the embedding is stale, or deform() was never called.
  const Eigen::MatrixX3d& update(const Lattice& lattice);

  /// The weight of control point `flat` at every embedded point, as the delta steps of
  /// update(lattice) that moved that control point alone evaluated and kept it (the weight each
  /// such step moved the points by): s * B_i(u) B_j(v) B_k(w) for the points whose cell's window
  /// holds the control point, 0 for the others and for points left unchanged, in original point
  /// order (#points). These are controlPointWeights()'s values computed by the deformer's SIMD
  /// kernels, which may round differently (fused multiply-adds: ~1e-16 relative). A consumer that
  /// follows a drag (the first step of the view's normals) reads them instead of evaluating the
  /// basis a second time. `weights` is resized only when its size differs.
  /// @return false, leaving `weights` untouched, when no kept weights of that control point match
  ///   `lattice` (another control point, another rest revision, a rational lattice).
  bool keptControlWeights(const Lattice& lattice, Eigen::Index flat, Eigen::VectorXd& weights) const;

  /// The last deformed points, #points x 3, world.
  const Eigen::MatrixX3d& points() const { return output_; }
  /// points(), handed over without a copy; the deformer keeps its embedding but no output (call
  /// deform() before the next update()).
  Eigen::MatrixX3d takePoints();
  /// Work of the last deform() / update() (points evaluated, control points changed).
  const DeformStats& lastStats() const { return stats_; }
  /// LOCAL control points of the last deform() / update() (what update() compares against);
  /// empty before the first deform().
  const Eigen::MatrixX3d& lastControlPoints() const { return lastControl_; }
  /// Weights of the last deform() / update() (empty before the first deform(); all 1 for a
  /// polynomial lattice).
  const Eigen::VectorXd& lastWeights() const { return lastWeights_; }
  /// True when the last deform() / update() ran with the lattice's current control points and
  /// weights (an update() now would change nothing).
  bool isCurrentFor(const Lattice& lattice) const {
    return deformed_ && lastControl_.rows() == lattice.pointCount() && lastControl_ == lattice.controlPoints() &&
           lastWeights_ == lattice.weights();
  }

  /// Run on all OpenMP threads (default) or on the calling thread only.
  void setParallel(bool parallel) { parallel_ = parallel; }
  /// The precision of the following calls (default Double). An exact update() is bit-identical
  /// to a deform() of the same precision; change it only before a deform().
  void setPrecision(Precision precision) { precision_ = precision; }
  /// The precision of the following calls.
  Precision precision() const { return precision_; }

 private:
  // Dense evaluation of the blocks whose cell is set in cellFilter (all if null); returns the
  // number of points evaluated.
  Eigen::Index evaluateBlocks(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& input,
                              const std::vector<char>* cellFilter);
  // Cells whose window holds a control point whose position or weight changed since the last
  // call; `changed` counts those control points.
  std::vector<char> touchedCells(const Lattice& lattice, Eigen::Index& changed) const;
  // The rational paths (rational_deform.cpp): a dense evaluation of the cells set in cellFilter
  // (all if null), out = Q + s F.linear (X - Xbar) from `input`, or without it (null)
  // out += s F.linear (X - Xlast) against the last control points and weights; and the delta
  // step of update(lattice).
  Eigen::Index evaluateRational(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>* input,
                                const std::vector<char>* cellFilter);
  const Eigen::MatrixX3d& updateRational(const Lattice& lattice);
  void remember(const Lattice& lattice);

  Embedding embedding_;
  Eigen::MatrixX3d output_;
  Eigen::MatrixX3d lastControl_;  // local control points at the last deform()/update()
  Eigen::VectorXd lastWeights_;   // weights at the last deform()/update()
  bool lastRational_ = false;     // the output of the last call came from the rational path
  // Rational path: per sorted point, the denominator D = sum B w of the last call; valid (for
  // every point) when denominatorsValid_.
  std::vector<double> denominators_;
  bool denominatorsValid_ = false;
  // update(lattice) after one control point moved (a drag's steps): that control point's weight
  // at each sorted point of the cells its change touched, kept by the step that computed them
  // (8 bytes per point) so that the next steps of the same control point read it instead of the
  // parameters (detail::weightedBlock, the same bits). Valid for control point stepWeightsControl_
  // (-1: none) of the lattice at rest revision stepWeightsRest_ (the embedding's).
  Eigen::VectorXd stepWeights_;
  Eigen::Index stepWeightsControl_ = -1;
  std::uint64_t stepWeightsRest_ = 0;
  bool deformed_ = false;
  bool parallel_ = true;
  Precision precision_ = Precision::Double;
  DeformStats stats_;
};

}  // namespace ffdkit::ffd
