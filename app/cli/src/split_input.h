#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>

#include <Eigen/Core>

#include "batch_ranks.h"
#include "ffdkit/meshio/mesh_data.h"
#include "ffdkit/meshio/read_limits.h"
#include "ffdkit/meshio/vertex_slices.h"

namespace ffdkit::cli {

/// One large INPUT deformed by every rank of an mpirun batch (docs/scaling.md): each rank reads
/// only its slice of the vertices (binary PLY and .npy: records [r n / N, (r+1) n / N); .xyz:
/// the lines that start in bytes [r S / N, (r+1) S / N)), deforms it, and writes it at its place
/// in the one output file. A PLY's faces and edges are read, checked and written by rank 0 only
/// (deforming moves only vertices); the output is byte for byte what one process writes.
/// Every method is collective: all ranks call it in the same order.
class SplitInput {
 public:
  /// A batch of several ranks given one INPUT splits it.
  static bool applies(std::size_t inputs, const BatchRanks& ranks) { return ranks.size() > 1 && inputs == 1; }

  /// Reads this rank's slice of `path` (rank 0 also the cells). Every rank fails when one does.
  /// The whole file's points are charged to `limits` before any slice is read, so that a batch
  /// refuses what one process refuses, whatever the number of ranks.
  /// @throws meshio::MeshIoError naming the file, the element and (xyz) the line, or the limit.
  SplitInput(const std::filesystem::path& path, const meshio::ReadLimits& limits, const BatchRanks& ranks);

  /// This rank's points (#slice x 3), moved out.
  Eigen::MatrixX3d takePoints() { return std::move(points_); }
  std::int64_t totalPoints() const { return totalPoints_; }

  /// Fails unless `target` can be written in slices (.ply, .npy, .xyz; a PLY of a mesh with
  /// normals cannot: a vertex's normal needs its neighbours, which other ranks hold).
  void checkTarget(const std::filesystem::path& target) const;

  /// Writes every rank's deformed slice into `target`, one file: rank 0 stages it (the header)
  /// beside `target`, every rank writes its slice at its offset (the sum of the byte counts of
  /// the ranks before it, after the header), rank 0 the faces after the last vertex, and rank 0
  /// renames it into place only when every rank has written its part; else it is removed.
  void write(const std::filesystem::path& target, const Eigen::MatrixX3d& deformed, const BatchRanks& ranks) const;

 private:
  std::filesystem::path path_;
  Eigen::MatrixX3d points_;
  std::int64_t totalPoints_ = 0;
  bool normalsAndFaces_ = false;
  meshio::MeshData cells_;  ///< rank 0: the PLY's faces and edges
};

}  // namespace ffdkit::cli
