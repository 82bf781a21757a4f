#include "json_text.h"

#include <algorithm>

namespace ffdkit::scenes::detail {
namespace {

using Json = nlohmann::ordered_json;

constexpr std::size_t kLineWidth = 100;

bool isScalar(const Json& v) { return !v.is_object() && !v.is_array(); }

// Arrays that read best on one line: scalars, or arrays of scalars (a matrix row, a point).
bool isCompact(const Json& v) {
  if (!v.is_array()) return false;
  for (const auto& e : v)
    if (!isScalar(e) && !(e.is_array() && std::all_of(e.begin(), e.end(), isScalar))) return false;
  return true;
}

void write(const Json& v, int indent, std::string& out) {
  const std::string pad(std::size_t(indent), ' ');
  const std::string inner(std::size_t(indent) + 2, ' ');
  if (isScalar(v)) {
    out += v.dump();
    return;
  }
  if (v.empty()) {
    out += v.is_array() ? "[]" : "{}";
    return;
  }
  if (isCompact(v)) {
    const std::string line = v.dump(-1, ' ', false);
    // nlohmann's compact dump has no spaces; add one after commas for readability.
    std::string spaced;
    bool inString = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      if (c == '"' && (i == 0 || line[i - 1] != '\\')) inString = !inString;
      spaced += c;
      if (c == ',' && !inString) spaced += ' ';
    }
    if (spaced.size() + std::size_t(indent) <= kLineWidth) {
      out += spaced;
      return;
    }
  }
  out += v.is_array() ? "[\n" : "{\n";
  bool first = true;
  if (v.is_array()) {
    for (const auto& e : v) {
      if (!first) out += ",\n";
      first = false;
      out += inner;
      write(e, indent + 2, out);
    }
  } else {
    for (const auto& item : v.items()) {
      if (!first) out += ",\n";
      first = false;
      out += inner + Json(item.key()).dump() + ": ";
      write(item.value(), indent + 2, out);
    }
  }
  out += "\n" + pad + (v.is_array() ? "]" : "}");
}

}  // namespace

std::string canonicalJsonText(const Json& value) {
  std::string out;
  write(value, 0, out);
  out += '\n';
  return out;
}

std::string lineColumn(const std::string& text, std::size_t byte) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return std::to_string(line) + ":" + std::to_string(column);
}

}  // namespace ffdkit::scenes::detail
