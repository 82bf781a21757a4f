#pragma once
// Frames of a scene's animation on the command line: --frame T, --frames A:B, out_%04d.png.

#include <filesystem>
#include <string>

#include "ffdkit/scenes/keyframes.h"

namespace ffdkit::cli {

/// An inclusive range of whole frames.
struct FrameRange {
  int first = 0;
  int last = 0;
};

/// Parses `--frame T` (a number; fractional frames lie between two frames) and checks that it is
/// inside the scene's frame range. @throws UsageError naming `option`, the range and the value.
double parseFrame(const std::string& text, const scenes::Animation& animation, const std::string& option = "--frame");

/// Parses `--frames A:B` (whole frames, A <= B) inside the scene's frame range.
/// @throws UsageError naming the option, the range and the value.
FrameRange parseFrameRange(const std::string& text, const scenes::Animation& animation);

/// Checks an output pattern: exactly one `%0Nd` (N = 1..9, e.g. out_%04d.png) and no other `%`.
/// @throws UsageError saying what was expected and what came.
void checkFramePattern(const std::string& pattern);
/// The pattern with its `%0Nd` replaced by `frame`, zero-padded to N digits as printf does.
std::filesystem::path framePath(const std::string& pattern, int frame);

}  // namespace ffdkit::cli
