#pragma once

// Comparing two documents written as text (scene files) that may differ in their numbers only:
// what a GUI test checks after undo, redo or frame changes reach a state by another path.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>

namespace ffdkit::app::testing {

/// The largest difference between the numbers of two texts that are the same but for their
/// numbers (each number relative to 1 + its size); nullopt when the rest differs.
inline std::optional<double> largestNumberDifference(const std::string& a, const std::string& b) {
  const auto isNumberStart = [](const std::string& t, std::size_t i) {
    return std::isdigit(static_cast<unsigned char>(t[i])) ||
           (t[i] == '-' && i + 1 < t.size() && std::isdigit(static_cast<unsigned char>(t[i + 1])));
  };
  double largest = 0.0;
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (isNumberStart(a, i) && isNumberStart(b, j)) {
      char* endA = nullptr;
      char* endB = nullptr;
      const double x = std::strtod(a.c_str() + i, &endA), y = std::strtod(b.c_str() + j, &endB);
      largest = std::max(largest, std::abs(x - y) / (1.0 + std::max(std::abs(x), std::abs(y))));
      i = static_cast<std::size_t>(endA - a.c_str());
      j = static_cast<std::size_t>(endB - b.c_str());
      continue;
    }
    if (a[i] != b[j]) return std::nullopt;
    ++i;
    ++j;
  }
  if (i != a.size() || j != b.size()) return std::nullopt;
  return largest;
}

}  // namespace ffdkit::app::testing
