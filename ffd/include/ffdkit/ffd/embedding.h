#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/ffd/cancelled.h"
#include "ffdkit/ffd/huge_pages.h"
#include "ffdkit/ffd/lattice.h"
#include "ffdkit/ffd/outside_policy.h"

namespace ffdkit::ffd {

/// Per-point result of embedding (Kuriyama 1996, eq. (6.2)).
enum class PointStatus : std::uint8_t {
  Inside,   ///< Xbar(u,v,w) = Q with (u,v,w) in the parameter box (epsilon-inclusive).
  Outside,  ///< outside the rest lattice; handled by the lattice's OutsidePolicy.
  Failed    ///< Newton did not converge; the point is left unchanged (like Identity).
};

/// Progress of a long computation: `done` of `total` units (points to embed) are finished.
/// Return true to go on, false to cancel (the computation then throws ffd::Cancelled).
/// Called on the thread that started the computation, never from an OpenMP worker, so it may
/// read an atomic cancel flag or store an atomic progress value without further locking.
using EmbedProgress = std::function<bool(Eigen::Index done, Eigen::Index total)>;

/// Options for embed().
struct EmbedOptions {
  double tolerance = 1e-13;       ///< Newton stops when |Xbar(uvw) - Q| <= tolerance * lattice.restSize().
  int maxIterations = 40;         ///< Newton iteration cap per point (after the initial guess).
  double boundaryEpsilon = 1e-9;  ///< inside test: uvw within the box grown by this fraction of its size.
  bool parallel = true;           ///< use all threads (OpenMP) over points.
  /// Optional progress / cancel hook (empty: none). embed() calls it on the calling thread with
  /// (0, n) before any work, about every kEmbedProgressChunk solved points, and with (n, n) once
  /// the Embedding is complete; `done` increases from call to call. Returning false (at any
  /// call, the last included) stops every thread after its current tile of 4096 points and
  /// makes embed() throw ffd::Cancelled, returning nothing. Cost: one call per chunk.
  EmbedProgress progress = {};
};

/// Points solved between two EmbedOptions::progress calls: ~60 ms of Newton embedding on one
/// thread for the benchmark lattices. Single-threaded (parallel = false or fewer than 16384
/// points) the calls fall exactly on multiples of it; in parallel the calling thread makes the
/// call when it finishes a block after the count of solved points passed the next multiple.
inline constexpr Eigen::Index kEmbedProgressChunk = 65536;

/// std::allocator whose resize() leaves new elements default-initialised (no zero fill): the
/// embedding's per-point arrays are written exactly once, in parallel, right after allocation,
/// and a zero fill first would double the memory traffic of a closed-form embedding.
template <class T>
struct NoInitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = NoInitAllocator<U>;
  };
  NoInitAllocator() = default;
  template <class U>
  NoInitAllocator(const NoInitAllocator<U>&) noexcept {}
  /// Large blocks are backed by huge pages where the system allows (adviseHugePages).
  T* allocate(std::size_t n) {
    T* p = std::allocator<T>::allocate(n);
    adviseHugePages(p, n * sizeof(T));
    return p;
  }
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// The (u,v,w) parameters of a set of object points in one lattice's rest lattice: the
/// precompute half of FFD (Kuriyama 1996, sec. 6.3.2: computed once when the object is attached,
/// again only when the rest lattice moves relative to the object; editing never re-embeds).
///
/// Internally the points are grouped by lattice cell so that deformation streams the same
/// control points over many points (see docs/ffd-engine.md). Memory: 29 bytes per point
/// (3 doubles, a 32-bit index, a status byte), a 28-byte record per block (about 3 bytes per
/// point for many-cell lattices in random point order), + 8 bytes per ClampEdge/Falloff point.
class Embedding {
 public:
  /// Per-point parameters (one axis), in sorted order, allocated without zeroing.
  using ParameterVector = std::vector<double, NoInitAllocator<double>>;
  /// Point indices (32-bit), allocated without zeroing.
  using IndexVector = std::vector<std::uint32_t, NoInitAllocator<std::uint32_t>>;
  /// Per-point statuses, allocated without zeroing.
  using StatusVector = std::vector<PointStatus, NoInitAllocator<PointStatus>>;

  Embedding() = default;

  /// Number of embedded points.
  Eigen::Index pointCount() const { return static_cast<Eigen::Index>(status_.size()); }
  /// Status of point `point` (original order). @throws LatticeError on a bad index.
  PointStatus status(Eigen::Index point) const;
  /// Status of every point, original order.
  const StatusVector& statuses() const { return status_; }
  /// Points inside the rest lattice.
  Eigen::Index insideCount() const { return inside_; }
  /// Points outside the rest lattice (handled by the outside policy).
  Eigen::Index outsideCount() const { return outside_; }
  /// Points whose Newton embedding did not converge (left unchanged by deformation).
  Eigen::Index failedCount() const { return failed_; }

  /// Parameters used to evaluate each point, pointCount x 3, original order: the Newton / closed-form
  /// solution for inside points and Extrapolate; the clamped solution for ClampEdge / Falloff;
  /// the unclamped solution for Identity outside points; the last Newton iterate clamped into the
  /// box for Failed points. Periodic parameters are wrapped into [0, 1).
  Eigen::MatrixX3d parameters() const;

  /// The lattice state this embedding was built for.
  std::uint64_t restRevision() const { return restRevision_; }
  /// Control-point counts of the lattice this embedding was built for.
  Eigen::Vector3i latticeCounts() const { return counts_; }
  /// The outside policy this embedding was built for.
  const OutsidePolicy& outsidePolicy() const { return policy_; }
  /// @throws LatticeError if `lattice` is not the one (same counts, same restRevision) this embedding
  /// was built for: "embedding is stale: built for rest revision 12, lattice is at 15; re-embed".
  void checkLattice(const Lattice& lattice) const;

  /// Heap bytes held (for the memory budget of the benchmarks).
  std::size_t memoryBytes() const;

  // Layout shared with Deformer (not for other callers). The points are cut into tiles of
  // kTileSize consecutive points (original order); inside a tile they are sorted by
  // (kind, lattice cell) into blocks, so that a block streams one cell's control points over
  // its points while reads and writes in original order stay within the tile (cache-local).
  static constexpr std::uint32_t kTileSize = 4096;  ///< Points per tile.
  /// How the points of a block are evaluated.
  enum class BlockKind : std::uint8_t {
    Evaluated,  ///< inside points, and Extrapolate outside points
    Blended,    ///< ClampEdge / Falloff outside points: weight blendWeight()[blendOffset + q - begin]
    Frozen      ///< left unchanged: Identity outside, Failed, beyond the Falloff distance
  };
  /// A run of sorted points of one tile that share a lattice cell and a BlockKind.
  struct Block {
    std::uint32_t cell;         ///< flat cell index i + cu (j + cv k) (cu, cv: cells along u, v; cellOf decodes it)
    std::uint32_t begin;        ///< sorted positions [begin, end)
    std::uint32_t end;  ///< end of the block's sorted positions (one past the last).
    std::uint32_t blendOffset;  ///< Blended only
    BlockKind kind;  ///< how the block's points are evaluated.
  };
  // 20 bytes: many-cell lattices in random order make blocks of a few points each, and the
  // embedding's memory per point (issue 21: <= 32 bytes) counts them.
  static_assert(sizeof(Block) == 20);
  /// The blocks of every tile, tile after tile.
  const std::vector<Block>& blocks() const { return blocks_; }
  /// A block's cell index per axis.
  std::array<int, 3> cellOf(const Block& block) const {
    const std::uint32_t cu = std::uint32_t(cellsU_), cv = std::uint32_t(cellsV_);
    return {int(block.cell % cu), int(block.cell / cu % cv), int(block.cell / cu / cv)};
  }
  /// Blocks of tile t: [tileBlocks()[t], tileBlocks()[t+1]).
  const std::vector<std::uint32_t>& tileBlocks() const { return tileBlocks_; }
  /// Parameter u of each point, sorted order.
  const ParameterVector& sortedU() const { return u_; }
  /// Parameter v of each point, sorted order.
  const ParameterVector& sortedV() const { return v_; }
  /// Parameter w of each point, sorted order.
  const ParameterVector& sortedW() const { return w_; }
  /// Original index of sorted position q; empty when the sorted order is the original order.
  const IndexVector& order() const { return order_; }
  /// Blend weights of the Blended blocks' points (ClampEdge / Falloff).
  const std::vector<double>& blendWeight() const { return blend_; }

 private:
  friend Embedding embed(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& points, const EmbedOptions& options);

  StatusVector status_;
  Eigen::Index inside_ = 0;
  Eigen::Index outside_ = 0;
  Eigen::Index failed_ = 0;
  std::uint64_t restRevision_ = 0;
  Eigen::Vector3i counts_ = Eigen::Vector3i::Zero();
  OutsidePolicy policy_{};
  std::vector<Block> blocks_;
  int cellsU_ = 1, cellsV_ = 1;  // cells along u and v (Block::cell)
  std::vector<std::uint32_t> tileBlocks_{0};
  ParameterVector u_, v_, w_;
  IndexVector order_;
  std::vector<double> blend_;
};

/// Embeds object points into the lattice's rest lattice: for each Q find (u,v,w) with
/// Xbar(u,v,w) = Q (Kuriyama 1996, eq. (6.2)).
/// - Affine rest map (box lattices, Lattice::restIsAffine()): closed form A^-1 (Q - b).
/// - Otherwise damped Newton on Xbar(uvw) - Q with the analytic Jacobian, starting from the
///   factored inverse of an untouched cylinder, the tabulated inverse (large inputs), the
///   cylindrical coordinates or the least-squares affine fit of the rest lattice; it stops as
///   soon as a Taylor bound certifies the next residual and restarts from the nearest sample of
///   a coarse grid when it fails; near-singular Jacobians (the axis of a solid cylinder) fall
///   back to a Levenberg-Marquardt step. On single-cell lattices of degree <= 3 the first two
///   steps run eight points at once (docs/ffd-engine.md, "Embedding (precompute) and Deformer").
/// The lattice's OutsidePolicy decides what outside points will do.
/// @param points  #points x 3, WORLD coordinates (lattice.frame() maps local to world), finite.
/// @throws LatticeError on non-finite points or more than 2^32-1 points.
/// @throws Cancelled when options.progress returns false (see EmbedOptions::progress).
Embedding embed(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& points,
                const EmbedOptions& options = {});

}  // namespace ffdkit::ffd
