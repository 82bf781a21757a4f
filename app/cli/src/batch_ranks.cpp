#include "batch_ranks.h"

#include <algorithm>
#include <cstdlib>
#include <vector>

#if FFDKIT_HAS_MPI
#include <mpi.h>
#endif

namespace ffdkit::cli {

namespace {

#if FFDKIT_HAS_MPI
// Open MPI, MPICH and Slurm launchers set one of these; a plain run must not pay for (or, as
// root, be refused) an MPI singleton start.
bool startedByLauncher() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}
#endif

}  // namespace

BatchRanks::BatchRanks() {
#if FFDKIT_HAS_MPI
  if (!startedByLauncher()) return;
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) MPI_Init(nullptr, nullptr);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  joined_ = true;
#endif
}

BatchRanks::~BatchRanks() {
#if FFDKIT_HAS_MPI
  if (joined_) MPI_Finalize();
#endif
}

void BatchRanks::broadcast(std::string& text) const {
#if FFDKIT_HAS_MPI
  if (!joined_) return;
  unsigned long long length = text.size();
  MPI_Bcast(&length, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
  text.resize(length);
  // MPI counts are int: send in pieces of at most 1 GiB.
  constexpr unsigned long long kPiece = 1ull << 30;
  for (unsigned long long offset = 0; offset < length; offset += kPiece) {
    const int count = static_cast<int>(std::min(kPiece, length - offset));
    MPI_Bcast(text.data() + offset, count, MPI_CHAR, 0, MPI_COMM_WORLD);
  }
#else
  (void)text;
#endif
}

Eigen::AlignedBox3d BatchRanks::unite(const Eigen::AlignedBox3d& box) const {
#if FFDKIT_HAS_MPI
  if (!joined_) return box;
  // An empty box is (+max, -max): min of the mins and max of the maxes unite correctly.
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = box.min()[a];
    hi[a] = box.max()[a];
  }
  MPI_Allreduce(MPI_IN_PLACE, lo, 3, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, hi, 3, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return Eigen::AlignedBox3d(Eigen::Vector3d(lo[0], lo[1], lo[2]), Eigen::Vector3d(hi[0], hi[1], hi[2]));
#else
  return box;
#endif
}

std::int64_t BatchRanks::sum(std::int64_t value) const {
#if FFDKIT_HAS_MPI
  if (!joined_) return value;
  long long v = value;
  MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  return v;
#else
  return value;
#endif
}

std::int64_t BatchRanks::sumBefore(std::int64_t value) const {
#if FFDKIT_HAS_MPI
  if (!joined_) return 0;
  long long v = value, before = 0;
  MPI_Exscan(&v, &before, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  return rank_ == 0 ? 0 : before;  // MPI leaves rank 0's result undefined
#else
  (void)value;
  return 0;
#endif
}

bool BatchRanks::allOk(bool ok) const {
#if FFDKIT_HAS_MPI
  if (!joined_) return ok;
  int v = ok ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  return v == 1;
#else
  return ok;
#endif
}

}  // namespace ffdkit::cli
