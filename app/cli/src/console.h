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
  void carve(const std::string& phase, double ms);
  /// Prints the split on stdout (with --timings; also with --quiet: it was asked for).
  void printTimings() const;

 private:
  using Clock = std::chrono::steady_clock;
  void book(const std::string& phase, double ms);  ///< adds to the phase's total
  bool quiet_;
  bool progress_;
  bool timings_;
  Clock::time_point start_;
  std::string phase_;
  Clock::time_point stepStart_;
  double carved_ = 0.0;  ///< milliseconds of the current step booked elsewhere (carve)
  std::vector<std::pair<std::string, double>> split_;  ///< phase, milliseconds, in first-seen order
};

}  // namespace ffdkit::cli
