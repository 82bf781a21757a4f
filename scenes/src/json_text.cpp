#include "json_text.h"

namespace ffdkit::scenes::detail {
namespace {

bool isFlatArray(const Json& j) {
  if (!j.is_array()) return false;
  for (const Json& e : j)
    if (e.is_structured()) return false;
  return true;
}

bool isSmallObject(const Json& j) {
  if (!j.is_object() || j.empty() || j.size() > 3) return false;
  for (const auto& item : j.items())
    if (item.value().is_object() || (item.value().is_array() && !isFlatArray(item.value()))) return false;
  return true;
}

void print(std::string& out, const Json& j, int indent) {
  const std::string pad(static_cast<std::size_t>(indent) + 2, ' ');
  if (isSmallObject(j)) {
    out += "{";
    std::size_t k = 0;
    for (const auto& item : j.items()) {
      out += (k++ ? ", " : "") + Json(item.key()).dump() + ": ";
      print(out, item.value(), indent + 2);
    }
    out += "}";
  } else if (j.is_object()) {
    if (j.empty()) {
      out += "{}";
      return;
    }
    out += "{\n";
    std::size_t k = 0;
    for (const auto& item : j.items()) {
      out += pad + Json(item.key()).dump() + ": ";
      print(out, item.value(), indent + 2);
      out += ++k < j.size() ? ",\n" : "\n";
    }
    out += std::string(static_cast<std::size_t>(indent), ' ') + "}";
  } else if (isFlatArray(j)) {
    out += "[";
    for (std::size_t i = 0; i < j.size(); ++i) out += (i ? ", " : "") + j[i].dump();
    out += "]";
  } else if (j.is_array()) {
    out += "[\n";
    for (std::size_t i = 0; i < j.size(); ++i) {
      out += pad;
      print(out, j[i], indent + 2);
      out += i + 1 < j.size() ? ",\n" : "\n";
    }
    out += std::string(static_cast<std::size_t>(indent), ' ') + "]";
  } else {
    out += j.dump();
  }
}

}  // namespace

std::string canonicalJsonText(const Json& value) {
  std::string out;
  print(out, value, 0);
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
