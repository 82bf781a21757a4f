#pragma once

#include <cstddef>
#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace ffdkit::ffd {

/// Asks the kernel to back the untouched memory [data, data + bytes) with transparent huge pages
/// (2 MiB) where the system allows it (THP in "madvise" mode, Debian's default). A 1M-point
/// embedding and deformation, or a 1M-vertex mesh read, fill 60-90 MB of fresh memory: with
/// 4 KiB pages that is 15,000-22,000 page faults, which cost about as much as the arithmetic.
/// Only a hint: a no-op for blocks under 4 MiB, on other systems, or when the kernel declines.
/// Call it right after allocating, before the first write (pages already touched stay small).
inline void adviseHugePages([[maybe_unused]] void* data, [[maybe_unused]] std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHuge = std::uintptr_t(2) << 20;
  if (data == nullptr || bytes < 2 * kHuge) return;
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(data) + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(kHuge - 1);
  if (end > begin) (void)::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#endif
}

/// adviseHugePages for the whole storage of a dense Eigen matrix.
template <class Matrix>
void adviseHugePages(Matrix& matrix) {
  adviseHugePages(matrix.data(), static_cast<std::size_t>(matrix.size()) * sizeof(typename Matrix::Scalar));
}

}  // namespace ffdkit::ffd
