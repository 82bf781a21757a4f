#pragma once

#include <chrono>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace ffdkit::cli {

/// printf-style text for a result line (at most 1023 characters; longer text is cut).
std::string format(const char* fmt, auto... values) {
  char line[1024];
  std::snprintf(line, sizeof line, fmt, values...);
  return line;
}

/// What a command tells the user: results on stdout (unless --quiet), progress of long steps on
/// stderr (only when stderr is a terminal, or with --progress), and the --timings split.
class Console {
 public:
  Console(bool quiet, bool progress, bool timings);
  /// Closes an unfinished progress line (a step that threw) so the error starts on its own line.
  ~Console();
  Console(const Console&) = delete;
  Console& operator=(const Console&) = delete;

  /// A result line on stdout; silent with --quiet.
  void say(const std::string& line) const;
  /// A warning on stderr; shown even with --quiet.
  void warn(const std::string& line) const;

  /// Starts a timed step of the --timings split (`phase`: "read", "embed", ...); `what` is the
  /// progress text. Ends the previous step. Steps of one phase add up.
  void begin(const std::string& phase, const std::string& what);
  /// Ends the current step.
  void end();
  /// Books `ms` of the current step, measured inside it, to `phase` instead (listed before the
  /// step's own phase the first time): one pass that embeds and deforms reports both shares.
  /// `cpuMs`, when known (>= 0), is the process's CPU time of that share; else the step keeps it.
  void carve(const std::string& phase, double ms, double cpuMs = -1.0);
  /// Prints the split on stdout (with --timings; also with --quiet: it was asked for): a line of
  /// wall times, "timings (ms): read 29.7, ...", and one of the process's CPU time (every
  /// thread, user and system), "cpu (ms): read 31.2, ...".
  void printTimings() const;

 private:
  using Clock = std::chrono::steady_clock;
  struct Split {
    std::string phase;
    double ms = 0.0;     ///< wall time
    double cpuMs = 0.0;  ///< the process's CPU time
  };
  static double cpuNowMs();  ///< the process's CPU time so far
  void book(const std::string& phase, double ms, double cpuMs);  ///< adds to the phase's totals
  bool quiet_;
  bool progress_;
  bool timings_;
  Clock::time_point start_;
  std::string phase_;
  Clock::time_point stepStart_;
  double stepCpuStart_ = 0.0;  ///< cpuNowMs() at the step's start
  double carved_ = 0.0;  ///< milliseconds of the current step booked elsewhere (carve)
  double carvedCpu_ = 0.0;  ///< CPU milliseconds of the current step booked elsewhere
  std::vector<Split> split_;  ///< in first-seen order
};

}  // namespace ffdkit::cli
