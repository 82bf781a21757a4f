#include "json_value_spans.h"

namespace ffdkit::fuzz {

namespace {

using Spans = std::vector<ValueSpan, ArenaAllocator<ValueSpan>>;
constexpr std::size_t npos = std::string_view::npos;

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
bool endsScalar(char c) { return isSpace(c) || c == ',' || c == ':' || c == ']' || c == '}' || c == '[' || c == '{' || c == '"'; }

std::size_t skipSpace(std::string_view text, std::size_t at) {
  while (at < text.size() && isSpace(text[at])) ++at;
  return at;
}

// One past the closing quote of the string whose opening quote is at `at`; npos when not closed.
std::size_t stringEnd(std::string_view text, std::size_t at) {
  for (std::size_t i = at + 1; i < text.size(); ++i) {
    if (text[i] == '\\')
      ++i;
    else if (text[i] == '"')
      return i + 1;
  }
  return npos;
}

// What the scan expects next.
enum class Expect { value, valueOrClose, key, keyOrClose, separator };

}  // namespace

std::optional<Spans> valueSpans(std::string_view text, std::size_t maxDepth) {
  Spans spans;
  std::vector<std::size_t, ArenaAllocator<std::size_t>> open;  // the containers not closed yet
  std::string_view key;                                         // of the member whose value is next
  Expect expect = Expect::value;
  for (std::size_t i = skipSpace(text, 0);; i = skipSpace(text, i)) {
    if (expect == Expect::separator && open.empty()) {
      if (i != text.size()) return std::nullopt;
      return spans;
    }
    if (i == text.size()) return std::nullopt;
    const char c = text[i];
    const bool inObject = !open.empty() && text[spans[open.back()].begin] == '{';
    if (expect == Expect::separator || expect == Expect::valueOrClose || expect == Expect::keyOrClose) {
      if (c == (inObject ? '}' : ']') && !open.empty()) {
        spans[open.back()].end = ++i;
        open.pop_back();
        expect = Expect::separator;
        continue;
      }
      if (expect == Expect::separator) {
        if (c != ',') return std::nullopt;
        ++i;
        expect = inObject ? Expect::key : Expect::value;
        continue;
      }
      expect = expect == Expect::keyOrClose ? Expect::key : Expect::value;
    }
    if (expect == Expect::key) {
      const std::size_t end = c == '"' ? stringEnd(text, i) : npos;
      if (end == npos) return std::nullopt;
      key = text.substr(i + 1, end - i - 2);
      i = skipSpace(text, end);
      if (i == text.size() || text[i] != ':') return std::nullopt;
      ++i;
      expect = Expect::value;
      continue;
    }
    if (open.size() > maxDepth) return std::nullopt;
    spans.push_back({i, npos, key});
    key = {};
    if (c == '{' || c == '[') {
      open.push_back(spans.size() - 1);
      ++i;
      expect = c == '{' ? Expect::keyOrClose : Expect::valueOrClose;
      continue;
    }
    if (c == '"') {
      i = stringEnd(text, i);
      if (i == npos) return std::nullopt;
    } else {
      if (endsScalar(c)) return std::nullopt;
      while (i < text.size() && !endsScalar(text[i])) ++i;
    }
    spans.back().end = i;
    expect = Expect::separator;
  }
}

}  // namespace ffdkit::fuzz
