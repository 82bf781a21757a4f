#pragma once
// Tokens of an OpenFOAM file (OpenFOAM User Guide, sec. 4.2): blanks, newlines, `//` and `/* */`
// comments between tokens, words, quoted strings, numbers and punctuation, with the line kept
// for messages. Private to meshio: the OpenFOAM reader parses with it, and the points writer
// walks the same tokens to put new values where the old ones were.

#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <system_error>

#include <fast_float/fast_float.h>

#include "ffdkit/meshio/mesh_data.h"
#include "parse_support.h"

namespace ffdkit::meshio::detail {

class FoamScanner {
 public:
  FoamScanner(std::string_view text, const std::string& source, std::size_t pos = 0, int line = 1)
      : text_(text), source_(source), pos_(pos), line_(line) {}

  std::size_t pos() const { return pos_; }
  int line() const { return line_; }
  bool atEnd() const { return pos_ >= text_.size(); }
  std::size_t bytesLeft() const { return text_.size() - pos_; }
  char peek() const { return pos_ < text_.size() ? text_[pos_] : '\0'; }
  std::string_view text() const { return text_; }

  /// Skips blanks, newlines and comments. @throws MeshIoError for an unterminated `/*`.
  void skipSpace() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '\n') {
        ++line_;
        ++pos_;
      } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
        ++pos_;
      } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '/') {
        const std::size_t newline = text_.find('\n', pos_);
        pos_ = newline == std::string_view::npos ? text_.size() : newline;
      } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '*') {
        const int startLine = line_;
        const std::size_t close = text_.find("*/", pos_ + 2);
        if (close == std::string_view::npos) {
          line_ = startLine;
          fail("a '/*' comment is not closed");
        }
        for (std::size_t k = pos_; k < close; ++k) line_ += text_[k] == '\n';
        pos_ = close + 2;
      } else {
        return;
      }
    }
  }

  /// The next character after space, which must be `c`. `what` names what needs it ("point 3").
  void expect(char c, const Where& what) {
    skipSpace();
    if (peek() != c) fail(what.text() + ": expected '" + c + "', got " + shown());
    ++pos_;
  }
  /// Moves past the character at pos() (after peek()).
  void advance(std::size_t n = 1) { pos_ += n; }

  /// A word: characters up to space, a comment or one of ;{}()[]". Empty at such a character.
  std::string_view word() {
    skipSpace();
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !isDelimiter(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }
  /// A "quoted string" (no escapes in the headers ffdkit reads), without its quotes.
  std::string_view quoted(const Where& what) {
    skipSpace();
    if (peek() != '"') fail(what.text() + ": expected a quoted string, got " + shown());
    const std::size_t close = text_.find('"', pos_ + 1);
    if (close == std::string_view::npos) fail(what.text() + ": the quoted string is not closed");
    const std::string_view value = text_.substr(pos_ + 1, close - pos_ - 1);
    for (char c : value) line_ += c == '\n';
    pos_ = close + 1;
    return value;
  }

  /// A finite number. `where` names it in a message ("point 3").
  double scalar(const Where& where) {
    skipSpace();
    const char* first = text_.data() + pos_;
    const char* last = text_.data() + text_.size();
    if (first < last && *first == '+') ++first;
    double value = 0.0;
    const auto result = fast_float::from_chars(first, last, value);
    if (result.ec != std::errc() || (result.ptr < last && !isDelimiter(*result.ptr)))
      fail(where.text() + ": expected a number, got " + shown());
    if (!std::isfinite(value)) fail(where.text() + ": non-finite number " + shown());
    pos_ = std::size_t(result.ptr - text_.data());
    return value;
  }
  /// The span of the next number token (after space), without parsing it; for the writer.
  std::string_view numberToken() {
    skipSpace();
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !isDelimiter(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }
  /// A whole number in [lo, hi].
  std::int64_t label(const Where& where, std::int64_t lo, std::int64_t hi) {
    skipSpace();
    const char* first = text_.data() + pos_;
    const char* last = text_.data() + text_.size();
    if (first < last && *first == '+') ++first;
    std::int64_t value = 0;
    const auto result = std::from_chars(first, last, value);
    if (result.ec == std::errc::result_out_of_range) fail(where.text() + ": " + shown() + " is out of range");
    if (result.ec != std::errc() || (result.ptr < last && !isDelimiter(*result.ptr)))
      fail(where.text() + ": expected a whole number, got " + shown());
    if (value < lo || value > hi)
      fail(where.text() + ": " + std::to_string(value) + " is outside " + std::to_string(lo) + ".." + std::to_string(hi));
    pos_ = std::size_t(result.ptr - text_.data());
    return value;
  }

  /// The text at the cursor for a message: 'word', or "the end of the file".
  std::string shown() const {
    if (pos_ >= text_.size()) return "the end of the file";
    std::size_t end = pos_ + 1;
    while (end < text_.size() && end - pos_ < 24 && !isDelimiter(text_[end]) && !isDelimiter(text_[end - 1])) ++end;
    std::string token(text_.substr(pos_, end - pos_));
    for (char& c : token)
      if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) c = '?';
    return "'" + token + "'";
  }

  [[noreturn]] void fail(const std::string& message) const { failAt(line_, message); }
  /// A message about something on an earlier line (a list's size, found wrong at its end).
  [[noreturn]] void failAt(int line, const std::string& message) const {
    throw MeshIoError(source_ + ":" + std::to_string(line) + ": " + message);
  }
  const std::string& source() const { return source_; }

  static bool isDelimiter(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v' || c == ';' || c == '{' ||
           c == '}' || c == '(' || c == ')' || c == '[' || c == ']' || c == '"' || c == '/';
  }

 private:
  std::string_view text_;
  const std::string& source_;
  std::size_t pos_;
  int line_;
};

}  // namespace ffdkit::meshio::detail
