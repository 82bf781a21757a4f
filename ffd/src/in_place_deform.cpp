#include "ffdkit/ffd/in_place_deform.h"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <string>

namespace ffdkit::ffd {

namespace {

double processCpuSeconds() {
  timespec t{};
  ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// The size of the chunk that starts at `first` of `n` points: `chunk` points, or all that are
// left when fewer than kInPlaceMinChunk would remain after it.
Eigen::Index chunkAt(Eigen::Index first, Eigen::Index n, Eigen::Index chunk) {
  const Eigen::Index left = n - first;
  return left - chunk < kInPlaceMinChunk ? left : chunk;
}

}  // namespace

InPlaceDeformResult deformInPlace(const Lattice& lattice, Eigen::Ref<Eigen::MatrixX3d> points,
                                  const InPlaceDeformOptions& options) {
  const Eigen::Index n = points.rows();
  // Whole tiles, so that each chunk's tiles are the whole array's (Embedding::kTileSize), and at
  // least kInPlaceMinChunk points, so that each is embedded with the whole array's first guesses.
  constexpr Eigen::Index kTile = Embedding::kTileSize;
  const Eigen::Index chunk = std::max(kInPlaceMinChunk, (std::max<Eigen::Index>(1, options.chunkPoints) + kTile - 1) / kTile * kTile);
  InPlaceDeformResult result;
  const EmbedProgress& progress = options.embed.progress;
  Deformer deformer;
  for (Eigen::Index first = 0; first < n;) {
    const Eigen::Index m = chunkAt(first, n, chunk);
    auto rows = points.middleRows(first, m);
    if (!rows.allFinite())
      for (Eigen::Index r = 0; r < m; ++r)
        if (!rows.row(r).allFinite())
          throw LatticeError("deformInPlace: point " + std::to_string(first + r) + " is not finite");
    EmbedOptions embedOptions = options.embed;
    if (progress) {
      embedOptions.progress = [&progress, first, n](Eigen::Index done, Eigen::Index) { return progress(first + done, n); };
    }
    const auto start = std::chrono::steady_clock::now();
    const double cpuStart = processCpuSeconds();
    Embedding embedding = embed(lattice, rows, embedOptions);
    result.embedCpuSeconds += processCpuSeconds() - cpuStart;
    result.embedSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result.insidePoints += embedding.insideCount();
    result.outsidePoints += embedding.outsideCount();
    result.failedPoints += embedding.failedCount();
    // A deformer per chunk: its output buffer is the chunk's size and, freed and allocated again
    // at the same size, comes back from the allocator without new pages.
    deformer = Deformer(std::move(embedding));
    deformer.setPrecision(options.precision);
    rows = deformer.deform(lattice, rows);
    first += m;
  }
  if (n == 0 && progress && !progress(0, 0)) throw Cancelled("deformInPlace: cancelled");
  return result;
}

}  // namespace ffdkit::ffd
