// Internal to ffdkit-cli: how the process keeps the memory it frees.
#pragma once

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace ffdkit::cli {

/// Keeps freed memory in the process for the next allocation instead of giving it back to the
/// system: every allocation comes from the heap (no mmap per large block) and the heap is never
/// trimmed, and it grows 64 MiB at a time. A deformation frees large blocks and allocates others
/// of like size right after (the file's bytes once parsed, then the embedding; temporaries of
/// the embedding, then the output), and on this project's virtual machines memory a process
/// touches for the first time costs 1-4 ms per MB when the host has reclaimed it: a 1M-vertex
/// deformation spent 3-5 ms of its embedding and deformation faulting in fresh pages for blocks
/// it had just freed (docs/scaling.md). A short-lived batch process loses nothing by keeping them.
inline void keepFreedMemoryForReuse() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  mallopt(M_TOP_PAD, 64 << 20);
#endif
}

}  // namespace ffdkit::cli
