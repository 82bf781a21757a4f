#pragma once
// Private to scenes: reading and writing the JSON files ffdkit keeps (scenes, widget files).

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "ffdkit/meshio/read_limits.h"

namespace ffdkit::scenes::detail {

using Json = nlohmann::ordered_json;

/// The canonical text of a document: keys in insertion order, 2-space indentation, arrays of
/// scalars (points, matrix rows, id lists) and objects of at most three such values on one
/// line, shortest round-trip numbers, a trailing newline. Human-readable and deterministic,
/// so that reading a file ffdkit wrote and writing it again gives the same bytes.
std::string canonicalJsonText(const Json& value);

/// "line:column" (1-based) of byte offset `byte` in `text`, for parse-error messages.
std::string lineColumn(const std::string& text, std::size_t byte);

/// Parses `content` into nlohmann's document in one pass, charging the document's bytes to
/// `budget` as it is built: an upper bound of what each value, container (with its growth slack),
/// object key and long string takes, charged before it is added. A compact file ("[0,0,0,...]")
/// makes a document about ten times its size. Once the document would pass what the budget has
/// left, it is freed and the rest is only counted; then the whole count is charged, so the
/// budget's error gives the document's full size. Malformed text is counted up to the error.
/// @throws meshio::ReadLimitError over the budget (`what` names the document in its message);
///   otherwise Json::parse_error or Json::out_of_range as Json::parse throws them.
Json parseChargedJson(const std::string& content, meshio::ReadBudget& budget, std::string_view what);

/// Parses `content` while charging its document (parseChargedJson) to `budget`; a syntax error
/// becomes `Error("<source>:<line>:<column>: syntax error ...")`, a budget overrun
/// `Error("<source>: the parsed JSON of ...")`. Messages never quote the text (nlohmann's
/// "last read: '...'" is dropped): the position is enough, and the text may be another file's.
template <class Error>
Json parseJson(const std::string& content, const std::string& sourceName, meshio::ReadBudget& budget) {
  try {
    return parseChargedJson(content, budget, "the parsed JSON of " + std::to_string(content.size()) + " bytes");
  } catch (const meshio::ReadLimitError& e) {
    throw Error(sourceName + ": " + e.what());
  } catch (const Json::parse_error& e) {
    // nlohmann's message starts "[json.exception.parse_error.101] parse error at line ..."; keep its tail.
    std::string message = e.what();
    if (auto pos = message.find("syntax error"); pos != std::string::npos) message = message.substr(pos);
    if (auto pos = message.find("; last read: "); pos != std::string::npos) message.erase(pos);
    throw Error(sourceName + ":" + lineColumn(content, e.byte == 0 ? 0 : e.byte - 1) + ": " + message);
  } catch (const Json::out_of_range& e) {
    // A number beyond double range ("1e400") is refused by the parser this way, without a position.
    std::string message = e.what();
    if (auto pos = message.find("] "); pos != std::string::npos) message = message.substr(pos + 2);
    throw Error(sourceName + ": " + message);
  }
}

template <class Error>
Json parseJson(const std::string& content, const std::string& sourceName) {
  meshio::ReadBudget budget;
  return parseJson<Error>(content, sourceName, budget);
}

/// Where a value sits in the document being read (a JSON pointer), for error messages:
/// `tool.json /bindings/2/to: unknown widget 'w7'`. Errors are thrown as `Error`.
template <class Error>
struct JsonLocation {
  const std::string* source;
  std::string pointer;

  JsonLocation operator/(const std::string& key) const { return {source, pointer + "/" + key}; }
  JsonLocation operator/(std::size_t index) const { return {source, pointer + "/" + std::to_string(index)}; }
  std::string where() const { return *source + " " + (pointer.empty() ? "/" : pointer); }
  [[noreturn]] void fail(const std::string& message) const { throw Error(where() + ": " + message); }
};

/// Charges `count` points to `budget`; over it, an error at `at` with the budget's message.
template <class E>
void chargePoints(meshio::ReadBudget& budget, std::uint64_t count, std::string_view what, const JsonLocation<E>& at) {
  try {
    budget.chargePoints(count, what);
  } catch (const meshio::ReadLimitError& e) {
    at.fail(e.what());
  }
}

/// Charges `count` items of `bytesEach` bytes to `budget`; over it, an error at `at`.
template <class E>
void chargeBytes(meshio::ReadBudget& budget, std::uint64_t count, std::uint64_t bytesEach, std::string_view what,
                 const JsonLocation<E>& at) {
  try {
    budget.chargeBytes(count, bytesEach, what);
  } catch (const meshio::ReadLimitError& e) {
    at.fail(e.what());
  }
}

template <class E>
const Json& member(const Json& object, const char* key, const JsonLocation<E>& at) {
  if (!object.is_object()) at.fail(std::string("expected an object, got ") + object.type_name());
  if (!object.contains(key)) at.fail(std::string("missing key '") + key + "'");
  return object[key];
}

template <class E>
void checkObject(const Json& j, const JsonLocation<E>& at) {
  if (!j.is_object()) at.fail(std::string("expected an object, got ") + j.type_name());
}

template <class E>
void checkArray(const Json& j, const JsonLocation<E>& at) {
  if (!j.is_array()) at.fail(std::string("expected an array, got ") + j.type_name());
}

/// Every key of `object` must be in `allowed`: a typo is an error, not silently ignored.
template <class E>
void checkKeys(const Json& object, std::initializer_list<const char*> allowed, const JsonLocation<E>& at) {
  checkObject(object, at);
  for (const auto& item : object.items()) {
    bool known = false;
    for (const char* a : allowed) known = known || item.key() == a;
    if (known) continue;
    std::string list;
    for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    (at / item.key()).fail("unknown key '" + item.key() + "' (known: " + list + ")");
  }
}

template <class E>
double number(const Json& j, const JsonLocation<E>& at) {
  if (!j.is_number()) at.fail(std::string("expected a number, got ") + j.type_name());
  const double v = j.get<double>();
  if (!std::isfinite(v)) at.fail("expected a finite number");
  return v;
}

/// The one rule for every integer a scene file, a widget file, a keyframe or a generator
/// parameter holds (frames, counts, indices, stripes, degrees, sample counts): a whole number
/// in [lo, hi]. Returns why `value` breaks it ("" when it does not):
/// "expected an integer in [3, 4096], got 5.5". A JSON value must be written as an integer
/// (5.5, 5.0 and 1e3 are refused; so are int64 min and uint64 max when out of range).
std::string integerProblem(const Json& value, std::int64_t lo, std::int64_t hi);
/// The same rule for a number already read as a double (generator parameters, which a scene
/// holds as numbers): a whole number in [lo, hi].
std::string integerProblem(double value, std::int64_t lo, std::int64_t hi);

/// The integer `j`, checked by integerProblem; the error names its location.
template <class E>
std::int64_t integerIn(const Json& j, std::int64_t lo, std::int64_t hi, const JsonLocation<E>& at) {
  if (const std::string problem = integerProblem(j, lo, hi); !problem.empty()) at.fail(problem);
  return j.is_number_unsigned() ? static_cast<std::int64_t>(j.get<std::uint64_t>()) : j.get<std::int64_t>();
}

/// integerIn for values that are ints: [lo, hi] within int's range.
template <class E>
int intIn(const Json& j, int lo, int hi, const JsonLocation<E>& at) {
  return static_cast<int>(integerIn(j, lo, hi, at));
}

template <class E>
std::string text(const Json& j, const JsonLocation<E>& at) {
  if (!j.is_string()) at.fail(std::string("expected a string, got ") + j.type_name());
  return j.get<std::string>();
}

template <class E>
bool boolean(const Json& j, const JsonLocation<E>& at) {
  if (!j.is_boolean()) at.fail(std::string("expected true or false, got ") + j.type_name());
  return j.get<bool>();
}

template <class E>
Eigen::Vector3d vector3(const Json& j, const JsonLocation<E>& at) {
  checkArray(j, at);
  if (j.size() != 3) at.fail("expected 3 numbers, got " + std::to_string(j.size()) + " values");
  return {number(j[0], at / 0), number(j[1], at / 1), number(j[2], at / 2)};
}

}  // namespace ffdkit::scenes::detail
