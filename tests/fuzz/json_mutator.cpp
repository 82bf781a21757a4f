#include "json_mutator.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "json_mutator_arena.h"
#include "json_value_spans.h"

namespace ffdkit::fuzz {

namespace {

// Everything a call builds lives in the arena of that call (json_mutator_arena.h); the result is
// copied out as a std::string.
using String = std::basic_string<char, std::char_traits<char>, ArenaAllocator<char>>;
template <class T>
using Vector = std::vector<T, ArenaAllocator<T>>;
using Json = nlohmann::basic_json<nlohmann::ordered_map, std::vector, String, bool, std::int64_t, std::uint64_t, double,
                                  ArenaAllocator>;

// Deeper documents are left to byte mutation: writing them back (recursive) could overflow the stack.
constexpr int kMaxDepth = 128;

// A value of the document and where it sits.
struct Node {
  Json* value;
  Json* parent;     // null for the root
  String key;       // its name, when the parent is an object
  int depth;
};

bool collect(Json& value, Json* parent, String key, int depth, Vector<Node>& out) {
  if (depth > kMaxDepth) return false;
  out.push_back({&value, parent, std::move(key), depth});
  if (value.is_object()) {
    for (auto it = value.begin(); it != value.end(); ++it)
      if (!collect(it.value(), &value, it.key(), depth + 1, out)) return false;
  } else if (value.is_array()) {
    for (auto& element : value)
      if (!collect(element, &value, {}, depth + 1, out)) return false;
  }
  return true;
}

// Numbers at the edges of what a reader converts: counts, indices, sizes, coordinates. (Numbers
// allocate nothing, so these outlive the arena's calls.)
const std::vector<Json>& boundaryNumbers() {
  static const std::vector<Json> numbers = {
      Json(0), Json(-1), Json(1), Json(2), Json(3), Json(4), Json(7), Json(8), Json(16), Json(255), Json(256),
      Json(65535), Json(65536), Json(1000), Json(100000), Json(1000000), Json(1000000000),
      Json(std::numeric_limits<std::int32_t>::max()), Json(std::int64_t(std::numeric_limits<std::int32_t>::max()) + 1),
      Json(std::numeric_limits<std::int32_t>::min()), Json(std::int64_t(1) << 32), Json(std::int64_t(1) << 53),
      Json(std::numeric_limits<std::int64_t>::max()), Json(std::numeric_limits<std::int64_t>::min()),
      Json(std::numeric_limits<std::uint64_t>::max()), Json(1e308), Json(-1e308), Json(1.7976931348623157e308),
      Json(5e-324), Json(1e-300), Json(1e-9), Json(0.5), Json(-0.5), Json(1.5), Json(2.5), Json(-0.0), Json(1e15),
      Json(0.1), Json(1.0 / 3.0)};
  return numbers;
}

// Number text that is not JSON (or not representable), which a strict reader must refuse.
constexpr const char* kRawNumbers[] = {"NaN",   "-NaN",  "nan",   "Infinity", "-Infinity",  "inf",
                                       "1e999", "-1e999", "1e-999", "18446744073709551616",
                                       "-9223372036854775809", "99999999999999999999999999999", "0x10", "1.",
                                       ".5",    "01",    "1e",    "-",        "+1",         "1e+",
                                       "-0",    "2e308"};

// Strings that a reader may take as a path or a name.
const std::vector<std::string>& interestingStrings() {
  static const std::vector<std::string> strings = {
      "../x",
      "../../../../../../../../etc/passwd",
      "/etc/passwd",
      "/dev/zero",
      "/dev/urandom",
      "/proc/self/mem",
      "..",
      ".",
      "",
      " ",
      "/",
      "./",
      "a/../../b.obj",
      "sub/../../x.ply",
      "mesh.obj/..",
      "~/x.obj",
      "C:\\Windows\\win.ini",
      "\\\\server\\share\\x.obj",
      "file:///etc/passwd",
      std::string("x.obj\0.json", 11),
      "nonexistent.ply",
      "mesh.stl",
      "mesh.vtp",
      "scene.json",
      "tool.json",
      "%s%n%x%p",
      "\xff\xfe",
      "w0",
      "w-1",
      "l0",
      std::string(300, 'a') + ".obj",
      std::string(5000, 'x'),
      std::string(64, '/'),
  };
  return strings;
}

class Mutation {
 public:
  Mutation(Json& document, std::uint64_t seed) : document_(document), rng_(seed) {}

  // One mutation; false when the document is too deep or the chosen mutation did not apply.
  bool once() {
    nodes_.clear();
    if (!collect(document_, nullptr, {}, 0, nodes_)) return false;
    switch (below(8)) {
      case 0:
      case 1: return number();
      case 2:
      case 3: return array();
      case 4: return string();
      case 5: return key();
      default: return value();
    }
  }

  // The document as text, with the raw number texts in place of their placeholders.
  String text() const {
    String text = document_.dump(-1, ' ', false, Json::error_handler_t::replace);
    for (std::size_t i = 0; i < raw_.size(); ++i) {
      String placeholder(1, '"');
      placeholder.append(placeholder_(i)).push_back('"');
      const std::size_t at = text.find(placeholder);
      if (at != std::string::npos) text.replace(at, placeholder.size(), raw_[i]);
    }
    return text;
  }

 private:
  static String placeholder_(std::size_t i) {
    char digits[24];
    char* const end = std::to_chars(digits, digits + sizeof digits, i).ptr;
    return String("ffdkit-fuzz-raw-").append(digits, end);
  }

  std::size_t below(std::size_t n) { return n == 0 ? 0 : std::size_t(rng_() % n); }
  template <class T, std::size_t N>
  const T& pick(const T (&items)[N]) { return items[below(N)]; }
  template <class T, class Allocator>
  const T& pick(const std::vector<T, Allocator>& items) { return items[below(items.size())]; }

  template <class Predicate>
  Node* someNode(Predicate predicate) {
    Vector<Node*> matches;
    for (Node& node : nodes_)
      if (predicate(node)) matches.push_back(&node);
    return matches.empty() ? nullptr : matches[below(matches.size())];
  }

  bool number() {
    Node* node = someNode([](const Node& n) { return n.value->is_number(); });
    if (!node) return false;
    Json& v = *node->value;
    const double x = v.get<double>();
    switch (below(6)) {
      case 0:
      case 1: v = pick(boundaryNumbers()); break;
      case 2:
        raw_.push_back(pick(kRawNumbers));
        v = placeholder_(raw_.size() - 1);
        break;
      case 3:  // a fraction where a count or an index is expected
        v = v.is_number_integer() ? x + 0.5 : std::floor(x);
        break;
      case 4: {
        const double nudged[] = {x + 1, x - 1, -x, 2 * x, x * 1000, x / 2, x * 1e100};
        v = pick(nudged);
        if (v.get<double>() == std::floor(v.get<double>()) && std::abs(v.get<double>()) < 9e15)
          v = std::int64_t(v.get<double>());
        break;
      }
      default: v = -(std::int64_t(below(4)) + 1); break;
    }
    return true;
  }

  bool array() {
    Node* node = someNode([](const Node& n) { return n.value->is_array(); });
    if (!node) return false;
    Json& a = *node->value;
    const std::size_t n = a.size();
    switch (below(8)) {
      case 0:  // duplicate an element
        if (n == 0) return false;
        {
          const std::size_t i = below(n);
          Json copy = a[i];
          a.insert(a.begin() + std::ptrdiff_t(i), std::move(copy));
        }
        return true;
      case 1:  // drop an element
        if (n == 0) return false;
        a.erase(a.begin() + std::ptrdiff_t(below(n)));
        return true;
      case 2:  // repeat an element many times
        if (n == 0) return false;
        {
          const Json copy = a[below(n)];
          for (std::size_t k = 2 + below(62); k > 0; --k) a.push_back(copy);
        }
        return true;
      case 3:  // keep one or two elements (a 3-vector that is short)
        while (a.size() > 1 + below(2)) a.erase(a.end() - 1);
        return true;
      case 4:
        a = Json::array();
        return true;
      case 5:  // swap two elements (order-dependent references, keys out of order)
        if (n < 2) return false;
        std::swap(a[below(n)], a[below(n)]);
        return true;
      case 6: {  // huge counts in a small numeric array: [1000, 1000, 100], [2147483647, 2, 2]
        if (n == 0 || n > 4) return false;
        for (const Json& e : a)
          if (!e.is_number()) return false;
        const std::int64_t big[] = {1000, 100000, 1000000, 2147483647, 1 << 20, 46341, 0, -1, 1, 2, 100, 3};
        for (Json& e : a) e = pick(big);
        return true;
      }
      default:  // one more element like the last
        a.push_back(n == 0 ? Json(0) : Json(a[n - 1]));
        return true;
    }
  }

  bool string() {
    Node* node = someNode([](const Node& n) { return n.value->is_string(); });
    if (!node) return false;
    Json& s = *node->value;
    switch (below(4)) {
      case 0:
      case 1: {
        const std::string& string = pick(interestingStrings());
        s = String(string.data(), string.size());
        break;
      }
      case 2: {  // a name from elsewhere: references to the wrong widget, lattice or object
        Node* other = someNode([](const Node& n) { return n.value->is_string(); });
        s = *other->value;
        break;
      }
      default: {
        static const char* const kSuffixes[] = {"1", "x", "/..", ".json", "\n", " "};
        s = s.get_ref<const String&>() + pick(kSuffixes);
        break;
      }
    }
    return true;
  }

  bool key() {
    Node* member = someNode([](const Node& n) { return n.parent && n.parent->is_object(); });
    if (!member) return false;
    Json& object = *member->parent;
    switch (below(3)) {
      case 0:  // drop it
        object.erase(member->key);
        return true;
      case 1: {  // rename it: to a key used elsewhere, or to a near miss
        Node* other = someNode([](const Node& n) { return n.parent && n.parent->is_object(); });
        static const char* const kNearMisses[] = {"s", "_", "X", " "};
        String name = below(2) ? other->key : member->key + pick(kNearMisses);
        if (object.contains(name)) return false;
        Json value = std::move(*member->value);
        object.erase(member->key);
        object[name] = std::move(value);
        return true;
      }
      default: {  // copy it into another object
        Node* target = someNode([](const Node& n) { return n.value->is_object(); });
        if (!target) return false;
        Json value = *member->value;
        (*target->value)[member->key] = std::move(value);
        return true;
      }
    }
  }

  bool value() {
    Node* node = nodes_.size() > 1 ? &nodes_[1 + below(nodes_.size() - 1)] : &nodes_[0];
    if (below(2)) {  // another part of the document: an object where a number was, a list for a name
      Json copy = *pick(nodes_).value;
      *node->value = std::move(copy);
    } else {
      *node->value = otherKind(below(10));
    }
    return true;
  }

  // A value of one of ten kinds (made per call: strings, arrays and objects live in the arena).
  static Json otherKind(std::size_t i) {
    switch (i) {
      case 0: return Json(nullptr);
      case 1: return Json(true);
      case 2: return Json(false);
      case 3: return Json::object();
      case 4: return Json::array();
      case 5: return Json("");
      case 6: return Json(0);
      case 7: return Json("x");
      case 8: return Json::array({Json::array()});
      default: return Json::array({0, 0, 0});
    }
  }

  Json& document_;
  std::mt19937_64 rng_;
  Vector<Node> nodes_;
  Vector<std::string_view> raw_;
};

std::optional<Json> parse(std::string_view text) {
  Json document = Json::parse(text.begin(), text.end(), nullptr, false);
  if (document.is_discarded()) return std::nullopt;
  return document;
}

String compactText(const Json& document) { return document.dump(-1, ' ', false, Json::error_handler_t::replace); }

// The size of a scalar's compact JSON text, near enough to plan cuts (a string's escapes are not
// counted; shrinkJson checks the text it writes).
std::size_t scalarBytes(const Json& value) {
  char digits[32];
  if (value.is_number_integer() || value.is_number_unsigned()) {
    const auto end = value.is_number_unsigned() ? std::to_chars(digits, digits + 32, value.get<std::uint64_t>()).ptr
                                                : std::to_chars(digits, digits + 32, value.get<std::int64_t>()).ptr;
    return std::size_t(end - digits);
  }
  if (value.is_number_float()) return std::size_t(std::to_chars(digits, digits + 32, value.get<double>()).ptr - digits);
  if (value.is_string()) return value.get_ref<const String&>().size() + 2;
  if (value.is_boolean()) return value.get<bool>() ? 4 : 5;
  return 4;  // null, binary
}

// An object or array of the document, with the size of each of its members or elements (key and
// separator included), and where it sits: what shrinkJson drops from.
struct Container {
  Json* value;
  std::size_t parent;  // index of the container holding it; itself for the root
  std::size_t index;   // its position there
  Vector<String> keys;  // when an object
  Vector<std::size_t> bytes;
  Vector<bool> dropped;
};

// The size of `value`'s compact text, adding it (when an object or array) and every container below
// it to `out` (parents before their children); nullopt when deeper than kMaxDepth.
std::optional<std::size_t> measure(Json& value, std::size_t parent, std::size_t index, int depth,
                                   Vector<Container>& out) {
  if (depth > kMaxDepth) return std::nullopt;
  if (!value.is_object() && !value.is_array()) return scalarBytes(value);
  const std::size_t at = out.size();
  out.push_back({&value, at == 0 ? 0 : parent, index, {}, {}, {}});
  std::size_t total = 2 + (value.empty() ? 0 : value.size() - 1);  // brackets and commas
  std::size_t i = 0;
  for (auto it = value.begin(); it != value.end(); ++it, ++i) {
    const std::size_t keyBytes = value.is_object() ? it.key().size() + 3 : 0;  // "key":
    const std::optional<std::size_t> child = measure(it.value(), at, i, depth + 1, out);
    if (!child) return std::nullopt;
    if (value.is_object()) out[at].keys.push_back(it.key());
    out[at].bytes.push_back(keyBytes + *child + 1);
    total += keyBytes + *child;
  }
  out[at].dropped.assign(out[at].bytes.size(), false);
  return total;
}

bool insideDropped(const Vector<Container>& containers, std::size_t c) {
  for (; c != 0; c = containers[c].parent)
    if (containers[containers[c].parent].dropped[containers[c].index]) return true;
  return false;
}

// Marks a run of at least `least` bytes of consecutive members or elements of one container that
// are not dropped yet, starting at one chosen by `rng` among the starts that can reach `least`;
// returns the bytes marked, 0 when no run can reach `least`. Seven times in eight the run is one of
// several values smaller than `least` (points of a list, keys of a channel), so that most of the
// document stays; otherwise any, a whole section too.
std::size_t markRun(Vector<Container>& containers, std::size_t least, std::mt19937_64& rng) {
  Vector<std::pair<std::size_t, std::size_t>> fine, any;
  for (std::size_t c = 0; c < containers.size(); ++c) {
    if (insideDropped(containers, c)) continue;
    std::size_t suffix = 0;
    for (std::size_t i = containers[c].bytes.size(); i-- > 0;) {
      if (containers[c].dropped[i]) continue;
      suffix += containers[c].bytes[i];
      if (suffix < least) continue;
      any.emplace_back(c, i);
      if (containers[c].bytes[i] < least) fine.emplace_back(c, i);
    }
  }
  const auto& starts = !fine.empty() && rng() % 8 != 0 ? fine : any;
  if (starts.empty()) return 0;
  const auto [c, first] = starts[rng() % starts.size()];
  Container& container = containers[c];
  std::size_t marked = 0;
  for (std::size_t i = first; i < container.bytes.size() && marked < least; ++i)
    if (!container.dropped[i]) {
      container.dropped[i] = true;
      marked += container.bytes[i];
    }
  return marked;
}

// Erases what markRun marked: children before their parents, the last element first.
void eraseMarked(Vector<Container>& containers) {
  for (std::size_t c = containers.size(); c-- > 0;) {
    Container& container = containers[c];
    for (std::size_t i = container.bytes.size(); i-- > 0;) {
      if (!container.dropped[i]) continue;
      if (container.value->is_object())
        container.value->erase(container.keys[i]);
      else
        container.value->erase(container.value->begin() + std::ptrdiff_t(i));
    }
  }
}

}  // namespace

std::optional<std::string> shrinkJson(std::string_view text, std::uint64_t seed, std::size_t maxSize) {
  const Arena::Scope call;
  std::optional<Json> document = parse(text);
  if (!document) return std::nullopt;
  std::mt19937_64 rng(seed);
  bool cut = false;
  // Runs of at least an eighth of the excess each, planned on one measurement of the document; the
  // text written is checked again (the sizes do not count escapes).
  for (int pass = 0; pass < 8; ++pass) {
    const String result = compactText(*document);
    if (result.size() <= maxSize) return cut ? std::optional<std::string>(result) : std::nullopt;
    Vector<Container> containers;
    if (!measure(*document, 0, 0, 0, containers)) return std::nullopt;
    const std::size_t excess = result.size() - maxSize;
    const std::size_t least = std::max<std::size_t>(1, excess / 8);
    std::size_t marked = 0;
    while (marked < excess) {
      const std::size_t run = markRun(containers, least, rng);
      if (run == 0) break;
      marked += run;
    }
    if (marked == 0) return std::nullopt;
    eraseMarked(containers);
    cut = true;
  }
  return std::nullopt;
}

std::optional<std::string> mutateJson(std::string_view text, std::uint64_t seed, std::size_t maxSize) {
  const Arena::Scope call;
  const std::optional<Json> original = parse(text);
  if (!original) return std::nullopt;
  const String unchanged = compactText(*original);
  std::mt19937_64 rng(seed);
  for (int attempt = 0; attempt < 4; ++attempt) {
    Json document = *original;
    Mutation mutation(document, rng());
    bool changed = false;
    for (std::size_t k = 1 + rng() % 4; k > 0; --k) changed = mutation.once() || changed;
    if (!changed) continue;
    const String result = mutation.text();
    if (result != unchanged && result.size() <= maxSize) return std::string(result);
  }
  return std::nullopt;
}

std::optional<std::string> crossOverJson(std::string_view first, std::string_view second, std::uint64_t seed,
                                         std::size_t maxSize) {
  const Arena::Scope call;
  const auto into = valueSpans(first, std::size_t(kMaxDepth));
  const auto from = valueSpans(second, std::size_t(kMaxDepth));
  if (!into || !from) return std::nullopt;
  std::mt19937_64 rng(seed);
  const ValueSpan& target = (*into)[rng() % into->size()];
  Vector<const ValueSpan*> sameKey;
  for (const ValueSpan& span : *from)
    if (!target.key.empty() && span.key == target.key) sameKey.push_back(&span);
  const ValueSpan& source = sameKey.empty() ? (*from)[rng() % from->size()] : *sameKey[rng() % sameKey.size()];
  const std::string_view graft = second.substr(source.begin, source.end - source.begin);
  if (first.size() - (target.end - target.begin) + graft.size() > maxSize) return std::nullopt;
  std::string result(first.substr(0, target.begin));
  result.append(graft).append(first.substr(target.end));
  return result;
}

}  // namespace ffdkit::fuzz
