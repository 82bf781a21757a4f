// The one check of the consumer projects (tests/install/consumers/<component>/): prints each
// result; main() returns failures() == 0 ? 0 : 1.
#pragma once
#include <cstdio>

namespace consumer {
inline int& failureCount() {
  static int count = 0;
  return count;
}
inline void check(bool ok, const char* what) {
  std::printf("%s: %s\n", ok ? "ok" : "FAILED", what);
  if (!ok) ++failureCount();
}
inline int exitCode() { return failureCount() == 0 ? 0 : 1; }
}  // namespace consumer
