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

namespace {

// Counts what nlohmann's document of a text holds, without building it (json::sax_parse).
class DocumentSize {
 public:
  std::uint64_t bytes() const { return bytes_; }

  bool null() { return value(); }
  bool boolean(bool) { return value(); }
  bool number_integer(Json::number_integer_t) { return value(); }
  bool number_unsigned(Json::number_unsigned_t) { return value(); }
  bool number_float(Json::number_float_t, const Json::string_t&) { return value(); }
  bool string(Json::string_t& s) { return value() && text(s.size()); }
  bool binary(Json::binary_t& b) { return value() && text(b.size()); }
  bool start_object(std::size_t) { return value() && container(); }
  bool end_object() { return true; }
  bool start_array(std::size_t) { return value() && container(); }
  bool end_array() { return true; }
  // An ordered_json member is a (key, value) pair in a vector: the key's string beside the value.
  bool key(Json::string_t& k) { return add(2 * sizeof(Json::string_t)) && text(k.size()); }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) { return false; }

 private:
  // A value's slot in its container, twice over for a vector's growth slack.
  bool value() { return add(2 * sizeof(Json)); }
  // A container's own allocation (its vector and the allocator's header).
  bool container() { return add(64); }
  // Heap text beyond the small-string buffer.
  bool text(std::size_t size) { return add(size < 16 ? 0 : size + 1 + 16); }
  bool add(std::uint64_t bytes) {
    bytes_ += bytes;
    return true;
  }
  std::uint64_t bytes_ = 0;
};

}  // namespace

std::uint64_t parsedJsonBytes(const std::string& content) {
  DocumentSize size;
  Json::sax_parse(content, &size, nlohmann::detail::input_format_t::json, false);
  return size.bytes();
}

std::string integerProblem(const Json& value, std::int64_t lo, std::int64_t hi) {
  const std::string expected = "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got ";
  if (value.is_number_unsigned()) {
    const std::uint64_t v = value.get<std::uint64_t>();
    if (hi < 0 || v > static_cast<std::uint64_t>(hi) || (lo > 0 && v < static_cast<std::uint64_t>(lo))) return expected + value.dump();
    return "";
  }
  if (value.is_number_integer()) {
    const std::int64_t v = value.get<std::int64_t>();
    if (v < lo || v > hi) return expected + value.dump();
    return "";
  }
  if (value.is_number()) return expected + value.dump();
  return expected + value.type_name();
}

std::string integerProblem(double value, std::int64_t lo, std::int64_t hi) {
  if (std::isfinite(value) && value == std::floor(value) && value >= static_cast<double>(lo) && value <= static_cast<double>(hi))
    return "";
  return "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
         (std::isfinite(value) ? Json(value).dump() : std::string(std::isnan(value) ? "nan" : "an infinite number"));
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
