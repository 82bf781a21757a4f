#include "console.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace ffdkit::cli {

Console::Console(bool quiet, bool progress, bool timings)
    : quiet_(quiet), progress_(!quiet && (progress || ::isatty(STDERR_FILENO) == 1)), timings_(timings),
      start_(Clock::now()) {}

Console::~Console() {
  if (progress_ && !phase_.empty()) std::fprintf(stderr, "failed\n");
}

void Console::say(const std::string& line) const {
  if (!quiet_) std::printf("%s\n", line.c_str());
}

void Console::warn(const std::string& line) const { std::fprintf(stderr, "warning: %s\n", line.c_str()); }

void Console::begin(const std::string& phase, const std::string& what) {
  end();
  phase_ = phase;
  stepStart_ = Clock::now();
  if (progress_) {
    std::fprintf(stderr, "%s ... ", what.c_str());
    std::fflush(stderr);
  }
}

void Console::end() {
  if (phase_.empty()) return;
  const double ms = std::chrono::duration<double, std::milli>(Clock::now() - stepStart_).count();
  if (progress_) std::fprintf(stderr, "%.0f ms\n", ms);
  book(phase_, std::max(0.0, ms - carved_));
  carved_ = 0.0;
  phase_.clear();
}

void Console::carve(const std::string& phase, double ms) {
  if (phase_.empty()) return;
  book(phase, ms);
  carved_ += ms;
}

void Console::book(const std::string& phase, double ms) {
  for (auto& [name, total] : split_) {
    if (name == phase) {
      total += ms;
      return;
    }
  }
  split_.emplace_back(phase, ms);
}

void Console::printTimings() const {
  if (!timings_) return;
  const double total = std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
  std::string line = "timings (ms):";
  char item[96];
  for (const auto& [phase, ms] : split_) {
    std::snprintf(item, sizeof item, " %s %.1f,", phase.c_str(), ms);
    line += item;
  }
  std::snprintf(item, sizeof item, " total %.1f", total);
  line += item;
  std::printf("%s\n", line.c_str());
}

}  // namespace ffdkit::cli
