#pragma once

#include <cstdint>
#include <exception>
#include <stdexcept>
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
  /// The sum over the ranks before this one (0 on rank 0): where this rank's part of a file
  /// starts when every rank writes its part after those of the ranks before it.
  std::int64_t sumBefore(std::int64_t value) const;
  /// True when `ok` holds on every rank: the check each rank makes before a step that must not
  /// start while another rank failed (renaming the outputs), and that keeps a failed rank from
  /// leaving the others waiting in a later collective.
  bool allOk(bool ok) const;

 private:
  int rank_ = 0;
  int size_ = 1;
  bool joined_ = false;
};

/// Runs `work` on this rank, then every rank learns whether all succeeded: this rank's own error
/// propagates, and a rank whose work succeeded while another's failed throws too, so that no
/// rank goes on to wait in a collective for one that left. A collective inside `work` must be
/// reached by every rank (none may fail before it). One process: just `work`.
template <class Work>
void onEveryRank(const BatchRanks& ranks, Work&& work) {
  std::exception_ptr error;
  try {
    work();
  } catch (...) {
    error = std::current_exception();
  }
  const bool ok = ranks.allOk(!error);
  if (error) std::rethrow_exception(error);
  if (!ok) throw std::runtime_error("another process of the mpirun batch failed (its message says why)");
}

}  // namespace ffdkit::cli
