#include "ffdkit/meshio/read_limits.h"

#include "ffdkit/meshio/read_failures.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>

namespace ffdkit::meshio {

namespace {

constexpr std::uint64_t kUint64Max = std::numeric_limits<std::uint64_t>::max();

// a * b, or the largest value when the product does not fit: an overflowing count is over any limit.
std::uint64_t saturatingProduct(std::uint64_t a, std::uint64_t b) {
  if (a != 0 && b > kUint64Max / a) return kUint64Max;
  return a * b;
}

std::uint64_t saturatingSum(std::uint64_t a, std::uint64_t b) { return b > kUint64Max - a ? kUint64Max : a + b; }

// A whole or decimal number followed by an optional unit; `unitOf` maps the unit's first letter
// to its factor (0: not a unit).
std::uint64_t parseScaled(std::string_view text, std::string_view kind, std::uint64_t (*unitOf)(char),
                          std::string_view allowedSuffixes) {
  const std::string shown(text);
  auto bad = [&](const std::string& why) -> std::invalid_argument {
    return std::invalid_argument("'" + shown + "' is not " + std::string(kind) + " (" + why + ")");
  };
  std::size_t end = 0;
  while (end < text.size() && (std::isdigit(static_cast<unsigned char>(text[end])) || text[end] == '.' || text[end] == 'e' ||
                               text[end] == 'E' || ((text[end] == '+' || text[end] == '-') && end > 0 &&
                                                    (text[end - 1] == 'e' || text[end - 1] == 'E'))))
    ++end;
  // "1e9" is a number, but a trailing 'E' without digits after it would be read as exponent: a
  // unit is never E, so this is fine.
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + end, value);
  if (end == 0 || ec != std::errc() || ptr != text.data() + end) throw bad("expected a number with an optional unit");
  std::string_view rest = text.substr(end);
  std::uint64_t factor = 1;
  if (!rest.empty()) {
    factor = unitOf(rest[0]);
    if (factor == 0) throw bad("unknown unit '" + std::string(rest) + "'");
    rest.remove_prefix(1);
    bool suffixOk = rest.empty();
    for (std::size_t start = 0; !suffixOk && start < allowedSuffixes.size();) {
      const std::size_t bar = allowedSuffixes.find('|', start);
      const std::string_view suffix = allowedSuffixes.substr(start, bar == std::string_view::npos ? bar : bar - start);
      suffixOk = rest == suffix;
      if (bar == std::string_view::npos) break;
      start = bar + 1;
    }
    if (!suffixOk) throw bad("unknown unit '" + std::string(text.substr(end)) + "'");
  }
  const double scaled = value * double(factor);
  if (!std::isfinite(scaled) || scaled < 1.0 || scaled >= 1.8e19) throw bad("expected at least 1 and less than 1.8e19");
  if (scaled != std::floor(scaled)) throw bad("expected a whole number");
  return std::uint64_t(scaled);
}

std::uint64_t binaryUnit(char c) {
  switch (std::toupper(static_cast<unsigned char>(c))) {
    case 'K': return std::uint64_t(1) << 10;
    case 'M': return std::uint64_t(1) << 20;
    case 'G': return std::uint64_t(1) << 30;
    case 'T': return std::uint64_t(1) << 40;
    default: return 0;
  }
}

std::uint64_t decimalUnit(char c) {
  switch (c) {
    case 'k': case 'K': return 1'000;
    case 'M': return 1'000'000;
    case 'G': return 1'000'000'000;
    default: return 0;
  }
}

}  // namespace

std::string byteSizeText(std::uint64_t bytes) {
  char text[64];
  if (bytes < 1024) {
    std::snprintf(text, sizeof text, "%llu bytes", static_cast<unsigned long long>(bytes));
  } else {
    const char* units[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    double value = double(bytes) / 1024.0;
    int unit = 0;
    while (value >= 1024.0 && unit < 5) {
      value /= 1024.0;
      ++unit;
    }
    std::snprintf(text, sizeof text, "%.1f %s", value, units[unit]);
  }
  return text;
}

std::string outOfMemoryText(const ReadBudget& budget, std::string_view what) {
  std::string text = "out of memory while reading";
  if (!what.empty()) text.append(" ").append(what);
  text.append(" (the read had charged ").append(byteSizeText(budget.bytesCharged()));
  text.append(" of its limit of ").append(byteSizeText(budget.limits().maxMemoryBytes));
  text.append("; a lower --max-memory refuses such a file before it allocates)");
  return text;
}

void ReadBudget::chargeBytes(std::uint64_t count, std::uint64_t bytesEach, std::string_view what) {
  const std::uint64_t bytes = saturatingProduct(count, bytesEach);
  const std::uint64_t total = saturatingSum(bytes_, bytes);
  if (total > limits_.maxMemoryBytes) {
    std::string message = std::string(what) + ": " + std::to_string(count) + " items of " + std::to_string(bytesEach) +
                          " bytes need " + byteSizeText(bytes);
    if (bytes_ > 0) message += "; with what this read holds already (" + byteSizeText(bytes_) + ") that is";
    else message += ",";
    message += " over the read limit of " + byteSizeText(limits_.maxMemoryBytes) + " (--max-memory)";
    throw ReadLimitError(message);
  }
  bytes_ = total;
}

void ReadBudget::chargePoints(std::uint64_t count, std::string_view what) {
  const std::uint64_t total = saturatingSum(points_, count);
  if (total > limits_.maxPoints) {
    std::string message = std::string(what) + ": " + std::to_string(count) + " points";
    if (points_ > 0) message += "; with the " + std::to_string(points_) + " this read holds already that is";
    else message += "";
    message += " over the read limit of " + std::to_string(limits_.maxPoints) + " points (--max-points)";
    throw ReadLimitError(message);
  }
  chargeBytes(count, 3 * sizeof(double), what);
  points_ = total;
}

std::uint64_t parseByteSize(std::string_view text) {
  return parseScaled(text, "a size in bytes", binaryUnit, "B|iB");
}

std::uint64_t parseCount(std::string_view text) { return parseScaled(text, "a count", decimalUnit, ""); }

}  // namespace ffdkit::meshio
