#include "frames.h"

#include <cctype>
#include <charconv>
#include <cstdio>

#include "args.h"

namespace ffdkit::cli {
namespace {

std::string rangeText(const scenes::Animation& animation) {
  return std::to_string(animation.firstFrame) + ".." + std::to_string(animation.lastFrame);
}

int wholeFrame(const std::string& text, const std::string& what) {
  int value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end) throw UsageError(what + ": expected a whole frame number, got '" + text + "'");
  return value;
}

// The position and width N of the one "%0Nd" in `pattern`.
std::pair<std::size_t, std::size_t> token(const std::string& pattern) {
  const std::size_t at = pattern.find('%');
  const std::string expected = "-o: a frame sequence needs a pattern with exactly one %0Nd (N = 1..9), e.g. out_%04d.png; got '" +
                               pattern + "'";
  if (at == std::string::npos || pattern.find('%', at + 1) != std::string::npos) throw UsageError(expected);
  if (at + 3 >= pattern.size() || pattern[at + 1] != '0' || !std::isdigit(static_cast<unsigned char>(pattern[at + 2])) ||
      pattern[at + 2] == '0' || pattern[at + 3] != 'd')
    throw UsageError(expected);
  return {at, 4};
}

}  // namespace

double parseFrame(const std::string& text, const scenes::Animation& animation, const std::string& option) {
  const double frame = parseNumber(text, option);
  if (frame < animation.firstFrame || frame > animation.lastFrame)
    throw UsageError(option + " " + text + " is outside the scene's frame range " + rangeText(animation));
  return frame;
}

FrameRange parseFrameRange(const std::string& text, const scenes::Animation& animation) {
  const auto colon = text.find(':');
  if (colon == std::string::npos) throw UsageError("--frames: expected A:B (first and last frame), got '" + text + "'");
  FrameRange range{wholeFrame(text.substr(0, colon), "--frames"), wholeFrame(text.substr(colon + 1), "--frames")};
  if (range.first > range.last)
    throw UsageError("--frames " + text + ": the first frame is after the last");
  if (range.first < animation.firstFrame || range.last > animation.lastFrame)
    throw UsageError("--frames " + text + " is outside the scene's frame range " + rangeText(animation));
  return range;
}

void checkFramePattern(const std::string& pattern) { (void)token(pattern); }

std::filesystem::path framePath(const std::string& pattern, int frame) {
  const auto [at, length] = token(pattern);
  char format[5] = {'%', '0', pattern[at + 2], 'd', '\0'};  // validated: "%0Nd", N = 1..9
  char digits[32];
  std::snprintf(digits, sizeof digits, format, frame);
  return pattern.substr(0, at) + digits + pattern.substr(at + length);
}

}  // namespace ffdkit::cli
