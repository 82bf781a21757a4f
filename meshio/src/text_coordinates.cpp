#include "text_coordinates.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <system_error>

#include <fast_float/fast_float.h>

namespace ffdkit::meshio::detail {

namespace {

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
bool isSpace(char c) { return isBlank(c) || c == '\n'; }

std::string shown(std::string_view token) {
  if (token.empty()) return "the end of the line";
  std::string text(1, '\'');
  text.append(token.substr(0, 40)).push_back('\'');
  return text;
}

// The text of `value` in `style`, at most `width` characters when width > 0; empty when it
// cannot fit.
std::string numberText(double value, const NumberStyle& style, std::size_t width) {
  char buffer[64];
  if (style.precision < 0) {
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, value).ptr;
    std::string text(buffer, end);
    if (width == 0 || text.size() <= width) return text;
    for (int digits = 16; digits >= 1; --digits) {
      std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
      if (std::strlen(buffer) <= width) return buffer;
    }
    return {};
  }
  for (int digits = style.precision; digits >= 0; --digits) {
    std::snprintf(buffer, sizeof buffer, "%.*E", digits, value);
    if (style.exponent != 'E')
      if (char* e = std::strchr(buffer, 'E')) *e = style.exponent;
    if (width == 0 || std::strlen(buffer) <= width) return buffer;
  }
  return {};
}

}  // namespace

void LineScanner::skipBlanks(bool newlines) {
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (isBlank(c)) {
      ++pos_;
    } else if (c == '\n' && newlines) {
      ++pos_;
      ++line_;
    } else {
      return;
    }
  }
}

bool LineScanner::atLineEnd() {
  skipBlanks(false);
  return pos_ >= text_.size() || text_[pos_] == '\n';
}

std::string_view LineScanner::takeLine() {
  const std::size_t newline = text_.find('\n', pos_);
  const std::size_t end = newline == std::string_view::npos ? text_.size() : newline;
  std::string_view line = text_.substr(pos_, end - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  if (newline != std::string_view::npos) {
    pos_ = newline + 1;
    ++line_;
  } else {
    pos_ = text_.size();
  }
  return line;
}

std::string_view LineScanner::token(bool newlines, char extraSeparator) {
  skipBlanks(newlines);
  const std::size_t start = pos_;
  while (pos_ < text_.size() && !isBlank(text_[pos_]) && text_[pos_] != '\n' &&
         (extraSeparator == '\0' || text_[pos_] != extraSeparator))
    ++pos_;
  return text_.substr(start, pos_ - start);
}

long long LineScanner::integer(std::string_view what, long long lo, long long hi, bool newlines) {
  const std::string_view t = token(newlines);
  const char* first = t.data() + (!t.empty() && t[0] == '+' ? 1 : 0);
  long long value = 0;
  const auto result = std::from_chars(first, t.data() + t.size(), value);
  if (result.ec == std::errc::result_out_of_range) fail(std::string(what) + ": " + shown(t) + " is out of range");
  if (result.ec != std::errc() || result.ptr != t.data() + t.size() || t.empty())
    fail(std::string(what) + ": expected an integer, got " + shown(t));
  if (value < lo || value > hi)
    fail(std::string(what) + ": " + std::to_string(value) + " is outside " + std::to_string(lo) + ".." + std::to_string(hi));
  return value;
}

double LineScanner::number(std::string_view what, bool newlines, std::size_t* start, std::size_t* length, bool fortran,
                           char extraSeparator) {
  const std::string_view t = token(newlines, extraSeparator);
  double value = 0.0;
  if (!parseNumberToken(t, value, fortran)) {
    double any = 0.0;
    const char* first = t.data() + (!t.empty() && t[0] == '+' ? 1 : 0);
    const auto result = fast_float::from_chars(first, t.data() + t.size(), any);
    if (!t.empty() && result.ec == std::errc() && result.ptr == t.data() + t.size() && !std::isfinite(any))
      fail(std::string(what) + ": non-finite number " + shown(t));
    fail(std::string(what) + ": expected a number, got " + shown(t));
  }
  if (start != nullptr) *start = std::size_t(t.data() - text_.data());
  if (length != nullptr) *length = t.size();
  return value;
}

void LineScanner::moveTo(std::size_t pos) {
  pos = std::min(pos, text_.size());
  if (pos > pos_ && !byteOffsets_) line_ += int(std::count(text_.begin() + std::ptrdiff_t(pos_), text_.begin() + std::ptrdiff_t(pos), '\n'));
  pos_ = pos;
}

void LineScanner::fail(const std::string& message) const {
  if (byteOffsets_) throw MeshIoError(source_ + ": byte offset " + std::to_string(pos_) + ": " + message);
  throw MeshIoError(source_ + ":" + std::to_string(line_) + ": " + message);
}

void LineScanner::failAt(int line, const std::string& message) const {
  if (byteOffsets_) fail(message);
  throw MeshIoError(source_ + ":" + std::to_string(line) + ": " + message);
}

bool parseNumberToken(std::string_view token, double& value, bool fortran) {
  if (token.empty() || token.size() > 64) return false;
  char buffer[65];
  std::size_t n = 0;
  for (char c : token) buffer[n++] = fortran && (c == 'D' || c == 'd') ? 'E' : c;
  const char* first = buffer + (buffer[0] == '+' ? 1 : 0);
  const auto result = fast_float::from_chars(first, buffer + n, value);
  return result.ec == std::errc() && result.ptr == buffer + n && std::isfinite(value);
}

std::string replaceCoordinates(std::string_view original, const CoordinateSpans& spans, const Eigen::MatrixX3d& points,
                               const std::string& source) {
  if (points.rows() != spans.pointCount())
    throw MeshIoError(source + ": " + std::to_string(points.rows()) + " points given for a file of " +
                      std::to_string(spans.pointCount()));
  std::string out;
  out.reserve(original.size() + original.size() / 8);
  std::size_t copied = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    for (int c = 0; c < spans.perPoint; ++c) {
      const std::size_t k = std::size_t(i) * std::size_t(spans.perPoint) + std::size_t(c);
      const std::size_t start = spans.starts[k], length = spans.lengths[k];
      const double value = points(i, c);
      // Unchanged values keep their text (a blank fixed-width field is a zero, as the readers take it).
      std::string_view old = original.substr(start, length);
      const std::size_t first = old.find_first_not_of(" \t\r");
      old = first == std::string_view::npos ? std::string_view() : old.substr(first, old.find_last_not_of(" \t\r") - first + 1);
      double was = 0.0;
      if (old.empty() ? (value == 0.0 && !std::signbit(value))
                      : parseNumberToken(old, was, spans.style.fortran) && std::memcmp(&was, &value, sizeof value) == 0)
        continue;
      if (!std::isfinite(value))
        throw MeshIoError(source + ": point " + std::to_string(i) + ": non-finite coordinate");
      const bool blankFirst = spans.style.separated && start > 0 && !isSpace(original[start - 1]);
      const std::size_t width = spans.style.fixedWidth ? length - (blankFirst && length > 0 ? 1 : 0) : 0;
      const std::string text = width == 0 && spans.style.fixedWidth ? std::string() : numberText(value, spans.style, width);
      if (text.empty())
        throw MeshIoError(source + ": point " + std::to_string(i) + ": " + std::to_string(value) + " does not fit a field of " +
                          std::to_string(length) + " characters");
      out.append(original.substr(copied, start - copied));
      if (spans.style.fixedWidth) out.append(length - text.size(), ' ');
      out.append(text);
      copied = start + length;
    }
  out.append(original.substr(copied));
  return out;
}

}  // namespace ffdkit::meshio::detail
