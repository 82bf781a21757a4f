#include "json_text.h"

#include <exception>
#include <utility>

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

// Counts what nlohmann's document of a text holds: an upper bound of its bytes, event by event
// (json::sax_parse's events).
class DocumentSize {
 public:
  std::uint64_t bytes() const { return bytes_; }

  void value() { add(2 * sizeof(Json)); }  // a value's slot in its container, twice over for a vector's growth slack
  void container() { add(64); }            // a container's own allocation (its vector and the allocator's header)
  void text(std::size_t size) { add(size < 16 ? 0 : size + 1 + 16); }  // heap text beyond the small-string buffer
  // An ordered_json member is a (key, value) pair in a vector: the key's string beside the value.
  void key(std::size_t size) {
    add(2 * sizeof(Json::string_t));
    text(size);
  }

 private:
  void add(std::uint64_t bytes) { bytes_ += bytes; }
  std::uint64_t bytes_ = 0;
};

// Builds the document with nlohmann's own DOM builder, counting each event's bytes before the
// builder allocates them. Past `allowed` bytes the document is freed and the rest only counted.
class ChargedDocument {
 public:
  explicit ChargedDocument(std::uint64_t allowed) : allowed_(allowed) {}

  Json& document() { return root_; }
  std::uint64_t bytes() const { return size_.bytes(); }
  // The parse error nlohmann reported (a parse_error or an out_of_range), or null.
  const std::exception_ptr& error() const { return error_; }

  bool null() { return value([&] { return dom_.null(); }); }
  bool boolean(bool v) { return value([&] { return dom_.boolean(v); }); }
  bool number_integer(Json::number_integer_t v) { return value([&] { return dom_.number_integer(v); }); }
  bool number_unsigned(Json::number_unsigned_t v) { return value([&] { return dom_.number_unsigned(v); }); }
  bool number_float(Json::number_float_t v, const Json::string_t& s) { return value([&] { return dom_.number_float(v, s); }); }
  bool string(Json::string_t& s) {
    size_.text(s.size());
    return value([&] { return dom_.string(s); });
  }
  bool binary(Json::binary_t& b) {
    size_.text(b.size());
    return value([&] { return dom_.binary(b); });
  }
  bool start_object(std::size_t n) {
    size_.container();
    return value([&] { return dom_.start_object(n); });
  }
  bool end_object() { return building_ ? dom_.end_object() : true; }
  bool start_array(std::size_t n) {
    size_.container();
    return value([&] { return dom_.start_array(n); });
  }
  bool end_array() { return building_ ? dom_.end_array() : true; }
  bool key(Json::string_t& k) {
    size_.key(k.size());
    return build([&] { return dom_.key(k); });
  }
  template <class Exception>
  bool parse_error(std::size_t, const std::string&, const Exception& e) {
    error_ = std::make_exception_ptr(e);
    return false;
  }

 private:
  template <class Add>
  bool value(Add add) {
    size_.value();
    return build(add);
  }
  template <class Add>
  bool build(Add add) {
    if (building_ && size_.bytes() > allowed_) {
      building_ = false;
      root_ = Json();  // the builder's pointers into it are never used again
    }
    return building_ ? add() : true;
  }

  std::uint64_t allowed_;
  DocumentSize size_;
  Json root_;
  nlohmann::detail::json_sax_dom_parser<Json> dom_{root_, true};
  bool building_ = true;
  std::exception_ptr error_;
};

}  // namespace

Json parseChargedJson(const std::string& content, meshio::ReadBudget& budget, std::string_view what) {
  const std::uint64_t limit = budget.limits().maxMemoryBytes;
  ChargedDocument document(limit > budget.bytesCharged() ? limit - budget.bytesCharged() : 0);
  Json::sax_parse(content, &document);
  budget.chargeBytes(1, document.bytes(), what);
  if (document.error()) std::rethrow_exception(document.error());
  return std::move(document.document());
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
