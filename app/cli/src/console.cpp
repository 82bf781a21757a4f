#include "console.h"

#include <time.h>
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

double Console::cpuNowMs() {
  timespec t{};
  ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e3 * double(t.tv_sec) + 1e-6 * double(t.tv_nsec);
}

void Console::begin(const std::string& phase, const std::string& what) {
  end();
  phase_ = phase;
  stepStart_ = Clock::now();
  stepCpuStart_ = cpuNowMs();
  if (progress_) {
    std::fprintf(stderr, "%s ... ", what.c_str());
    std::fflush(stderr);
  }
}

void Console::end() {
  if (phase_.empty()) return;
  const double ms = std::chrono::duration<double, std::milli>(Clock::now() - stepStart_).count();
  if (progress_) std::fprintf(stderr, "%.0f ms\n", ms);
  book(phase_, std::max(0.0, ms - carved_), std::max(0.0, cpuNowMs() - stepCpuStart_ - carvedCpu_));
  carved_ = carvedCpu_ = 0.0;
  phase_.clear();
}

void Console::carve(const std::string& phase, double ms, double cpuMs) {
  if (phase_.empty()) return;
  book(phase, ms, std::max(0.0, cpuMs));
  carved_ += ms;
  carvedCpu_ += std::max(0.0, cpuMs);
}

void Console::book(const std::string& phase, double ms, double cpuMs) {
  for (Split& split : split_) {
    if (split.phase == phase) {
      split.ms += ms;
      split.cpuMs += cpuMs;
      return;
    }
  }
  split_.push_back({phase, ms, cpuMs});
}

void Console::printTimings() const {
  if (!timings_) return;
  const double total = std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
  std::string line = "timings (ms):", cpu = "cpu (ms):";
  char item[96];
  for (const Split& split : split_) {
    std::snprintf(item, sizeof item, " %s %.1f,", split.phase.c_str(), split.ms);
    line += item;
    std::snprintf(item, sizeof item, " %s %.1f,", split.phase.c_str(), split.cpuMs);
    cpu += item;
  }
  std::snprintf(item, sizeof item, " total %.1f", total);
  line += item;
  std::snprintf(item, sizeof item, " total %.1f", cpuNowMs());
  cpu += item;
  std::printf("%s\n%s\n", line.c_str(), cpu.c_str());
}

}  // namespace ffdkit::cli
