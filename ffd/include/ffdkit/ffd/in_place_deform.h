#pragma once
// Deforming a caller's points in place: embed() and Deformer::deform() a chunk of points at a
// time, each chunk's result written back over its input, so that a mesh of millions of points is
// deformed without an embedding or an output of its size (Kuriyama 1996, sec. 6.3.2: the embedding
// is the precompute half of FFD; a one-shot deformation needs it only while its points are
// evaluated).

#include <Eigen/Core>

#include "ffdkit/ffd/deformer.h"
#include "ffdkit/ffd/embedding.h"
#include "ffdkit/ffd/lattice.h"

namespace ffdkit::ffd {

/// Options of deformInPlace().
struct InPlaceDeformOptions {
  /// How each chunk is embedded. `progress`, when set, is called with the points done over the
  /// whole array (the (0, n) and (n, n) calls included); `false` cancels (ffd::Cancelled).
  EmbedOptions embed;
  /// The precision of the deformation kernels (Deformer::setPrecision).
  Precision precision = Precision::Double;
  /// Points embedded and deformed at a time (rounded up to whole tiles of Embedding::kTileSize;
  /// never fewer than kInPlaceMinChunk, see there). About 60 bytes per point of it are held.
  Eigen::Index chunkPoints = Eigen::Index(1) << 18;
};

/// The fewest points of a chunk (but the only one, when the array holds fewer): embed() solves
/// non-affine rest maps from a tabulated inverse when it is given at least this many points, and
/// from another first guess below (which converges to other last bits), so that every chunk of
/// an array of at least this many points is embedded as the whole array would be.
inline constexpr Eigen::Index kInPlaceMinChunk = 65536;

/// What deformInPlace() did.
struct InPlaceDeformResult {
  Eigen::Index insidePoints = 0;   ///< points inside the rest lattice (Embedding::insideCount)
  Eigen::Index outsidePoints = 0;  ///< points outside it, handled by its outside policy
  Eigen::Index failedPoints = 0;   ///< points whose embedding did not converge, left unchanged
  double embedSeconds = 0.0;       ///< wall time spent embedding (the rest deformed)
  double embedCpuSeconds = 0.0;    ///< the process's CPU time (every thread) spent embedding
};

/// Deforms `points` (#P x 3 WORLD points, one per row, finite) by `lattice` in place: each point
/// ends bit for bit where embed(lattice, points) followed by Deformer::deform (with
/// options.precision) would put it, that is what an ffd::Pipeline of this one lattice gives. The
/// points are taken a chunk at a time (options.chunkPoints, whole tiles, at least
/// kInPlaceMinChunk): the chunk is embedded, deformed into a buffer of the chunk's size and copied
/// back. Memory: about 60 bytes per point of one chunk (its embedding and deformed points), none
/// per point of the array. Threads: as embed() and Deformer (OpenMP), chunk after chunk.
/// @throws LatticeError for a non-finite point (named by its row in `points`) and as embed() and
///         Deformer::deform() do; Cancelled when options.embed.progress returns false. Either way
///         the chunks before the one that threw are deformed and the others are as given.
InPlaceDeformResult deformInPlace(const Lattice& lattice, Eigen::Ref<Eigen::MatrixX3d> points,
                                  const InPlaceDeformOptions& options = {});

}  // namespace ffdkit::ffd
