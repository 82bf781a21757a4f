#pragma once

#include <cstdint>
#include <string>

#include <Eigen/Geometry>

namespace ffdkit::cli {

/// The processes of one `mpirun -n N ffdkit-cli deform ...` batch (docs/scaling.md). Without
/// MPI support (CMake option FFDKIT_MPI=OFF) or when not started by an MPI launcher, it is one
/// process of rank 0 and every collective is the identity, so the same code runs either way.
/// Collectives must be called by every rank in the same order.
class BatchRanks {
 public:
  /// Joins the MPI job when the process was started by mpirun (MPI_Init), else stays alone.
  BatchRanks();
  ~BatchRanks();  ///< MPI_Finalize when joined.
  BatchRanks(const BatchRanks&) = delete;
  BatchRanks& operator=(const BatchRanks&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool leader() const { return rank_ == 0; }

  /// Rank 0's `text` on every rank.
  void broadcast(std::string& text) const;
  /// The union of every rank's box.
  Eigen::AlignedBox3d unite(const Eigen::AlignedBox3d& box) const;
  /// The sum over ranks.
  std::int64_t sum(std::int64_t value) const;
  /// True when `ok` holds on every rank: the check each rank makes before a step that must not
  /// start while another rank failed (renaming the outputs), and that keeps a failed rank from
  /// leaving the others waiting in a later collective.
  bool allOk(bool ok) const;

 private:
  int rank_ = 0;
  int size_ = 1;
  bool joined_ = false;
};

}  // namespace ffdkit::cli
