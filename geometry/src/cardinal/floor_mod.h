#pragma once
// Internal: the index arithmetic of closed (periodic) knot and point sequences.

namespace ffdkit::geometry::cardinal::detail {

/// a mod m in [0, m) for m > 0, also for negative a (C++'s % keeps the sign of a).
inline int floorMod(int a, int m) { return ((a % m) + m) % m; }

}  // namespace ffdkit::geometry::cardinal::detail
