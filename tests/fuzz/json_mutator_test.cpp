#include "json_mutator.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "json_mutator_arena.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace ffdkit::fuzz {
namespace {

using Json = nlohmann::ordered_json;

constexpr const char* kScene =
    R"({"version":2,"objects":[{"name":"cube","mesh":"cube.obj","points":[0.25,1,2]}],)"
    R"("widgets":{"lattices":[{"id":"w0","counts":[3,3,3],"degree":2}]},"bindings":[{"from":"w0","to":"cube"}]})";

// The texts of 4000 mutations of kScene, by seed.
std::set<std::string> manyMutations(std::size_t maxSize = 1 << 16) {
  std::set<std::string> texts;
  for (std::uint64_t seed = 0; seed < 4000; ++seed)
    if (auto text = mutateJson(kScene, seed, maxSize)) texts.insert(*text);
  return texts;
}

bool anyContains(const std::set<std::string>& texts, const std::string& part) {
  for (const std::string& text : texts)
    if (text.find(part) != std::string::npos) return true;
  return false;
}

TEST(JsonMutator, LeavesTextThatIsNotJsonToByteMutation) {
  EXPECT_FALSE(mutateJson("{\"a\": [1, 2", 1, 1000));
  EXPECT_FALSE(mutateJson("", 1, 1000));
  EXPECT_FALSE(crossOverJson("{}", "[1,", 1, 1000));
}

TEST(JsonMutator, IsDeterministicPerSeedAndChangesTheDocument) {
  for (std::uint64_t seed = 0; seed < 200; ++seed) {
    const auto first = mutateJson(kScene, seed, 1 << 16);
    ASSERT_TRUE(first) << "seed " << seed;
    EXPECT_EQ(first, mutateJson(kScene, seed, 1 << 16)) << "seed " << seed;
    EXPECT_NE(*first, Json::parse(kScene).dump()) << "seed " << seed;
  }
}

TEST(JsonMutator, StaysWithinTheMaximumSize) {
  const std::size_t maxSize = std::string(kScene).size() + 20;
  std::size_t produced = 0;
  for (const std::string& text : manyMutations(maxSize)) {
    EXPECT_LE(text.size(), maxSize);
    ++produced;
  }
  EXPECT_GT(produced, 500u);  // most mutations fit; the long strings and repeats do not
}

TEST(JsonMutator, MostResultsAreJsonAndSomeCarryNumbersThatAreNot) {
  std::size_t json = 0, other = 0;
  for (const std::string& text : manyMutations()) (Json::accept(text) ? json : other)++;
  EXPECT_GT(json, 5 * other);
  EXPECT_GT(other, 50u);
}

TEST(JsonMutator, ReachesBoundaryNumbers) {
  const std::set<std::string> texts = manyMutations();
  for (const char* number : {":0,", "-1", "9223372036854775807", "-9223372036854775808", "18446744073709551615",
                             "2147483647", "1e+308", "0.5", "NaN", "1e999", "18446744073709551616"})
    EXPECT_TRUE(anyContains(texts, number)) << number;
  // A count of 3 made a fraction: "counts":[3.5,...
  EXPECT_TRUE(anyContains(texts, "3.5")) << "integer + 0.5";
}

TEST(JsonMutator, ChangesArrayLengthsAndSetsHugeCounts) {
  std::set<std::size_t> lengths;
  bool hugeCounts = false;
  for (const std::string& text : manyMutations()) {
    const Json document = Json::parse(text, nullptr, false);
    if (document.is_discarded() || !document.is_object() || !document.contains("widgets")) continue;
    const Json& widgets = document["widgets"];
    if (!widgets.is_object() || !widgets.contains("lattices") || !widgets["lattices"].is_array() ||
        widgets["lattices"].empty() || !widgets["lattices"][0].is_object())
      continue;
    const Json& lattice = widgets["lattices"][0];
    if (!lattice.contains("counts") || !lattice["counts"].is_array()) continue;
    lengths.insert(lattice["counts"].size());
    for (const Json& count : lattice["counts"])
      if (count.is_number_integer() && count.get<std::int64_t>() >= 1000) hugeCounts = true;
  }
  EXPECT_TRUE(lengths.count(0) && lengths.count(1) && lengths.count(2) && lengths.count(4)) << "dropped and duplicated";
  EXPECT_TRUE(*lengths.rbegin() > 10) << "repeated";
  EXPECT_TRUE(hugeCounts);
}

TEST(JsonMutator, PutsPathsAndOtherNamesIntoStrings) {
  const std::set<std::string> texts = manyMutations();
  EXPECT_TRUE(anyContains(texts, R"(:"../x")"));
  EXPECT_TRUE(anyContains(texts, R"(:"/etc/passwd")"));
  EXPECT_TRUE(anyContains(texts, std::string(300, 'a') + ".obj"));
  EXPECT_TRUE(anyContains(texts, R"("to":"w0")")) << "a name from elsewhere in the document";
}

TEST(JsonMutator, RenamesDropsAndCopiesKeys) {
  bool dropped = false, renamed = false, copied = false;
  for (const std::string& text : manyMutations()) {
    const Json document = Json::parse(text, nullptr, false);
    if (document.is_discarded() || !document.is_object()) continue;
    if (!document.contains("version") && document.contains("objects")) dropped = true;
    if (document.contains("versions")) renamed = true;
    if (document.contains("degree") || document.contains("mesh")) copied = true;  // from a nested object
  }
  EXPECT_TRUE(dropped);
  EXPECT_TRUE(renamed);
  EXPECT_TRUE(copied);
}

TEST(JsonMutator, CrossOverGraftsAValueOfTheSecondDocument) {
  const std::string first = R"({"counts":[2,2,2],"name":"a"})";
  const std::string second = R"({"counts":[9,8,7],"other":{"deep":[1]}})";
  std::set<std::string> texts;
  for (std::uint64_t seed = 0; seed < 300; ++seed)
    if (auto text = crossOverJson(first, second, seed, 1000)) {
      EXPECT_TRUE(Json::accept(*text)) << *text;
      texts.insert(*text);
    }
  EXPECT_TRUE(texts.count(R"({"counts":[9,8,7],"name":"a"})")) << "the value with the same key";
  EXPECT_TRUE(anyContains(texts, R"({"deep":[1]})"));
  EXPECT_FALSE(crossOverJson(first, second, 1, 5));
}

TEST(JsonMutator, CrossOverSplicesTheTextsAndKeepsTheRestOfTheFirst) {
  // Spaces and a number that is not JSON stay as they were around the graft.
  const std::string first = "{ \"a\": NaN,\n  \"b\": [1, 2] }";
  const std::string second = R"({"b":{"x":"}]"},"c":[true,null]})";
  std::set<std::string> texts;
  for (std::uint64_t seed = 0; seed < 200; ++seed)
    if (auto text = crossOverJson(first, second, seed, 1000)) texts.insert(*text);
  EXPECT_TRUE(texts.count("{ \"a\": NaN,\n  \"b\": {\"x\":\"}]\"} }")) << "the value with the same key";
  EXPECT_TRUE(texts.count("{ \"a\": NaN,\n  \"b\": [1, [true,null]] }")) << "an element replaced";
  EXPECT_TRUE(texts.count(R"({"x":"}]"})")) << "the root replaced";
  for (const std::string& text : texts) EXPECT_EQ(Json::accept(text), text.find("NaN") == std::string::npos) << text;
}

TEST(JsonMutator, CrossOverLeavesTextsWhoseStructureIsNotJsonToByteCrossOver) {
  for (const char* broken : {"", "[1,", "[1}", "{\"a\" 1}", "{\"a\":1,}", "[1,]", "{\"a\":1} x", "\"open", "{1:2}",
                             "[1 2]", "{\"a\":[}"})
    for (std::uint64_t seed = 0; seed < 20; ++seed) {
      EXPECT_FALSE(crossOverJson(broken, "[1]", seed, 1000)) << broken;
      EXPECT_FALSE(crossOverJson("[1]", broken, seed, 1000)) << broken;
    }
  EXPECT_TRUE(crossOverJson(std::string(100, '[') + std::string(100, ']'), "[1]", 1, 1000));
  EXPECT_FALSE(crossOverJson(std::string(200, '[') + std::string(200, ']'), "[1]", 1, 1000)) << "left to bytes, as mutation";
}

// kScene with a lattice of 64 points: 1.3 KB of compact JSON.
std::string longScene() {
  Json document = Json::parse(kScene);
  Json points = Json::array();
  for (int i = 0; i < 64; ++i) points.push_back(Json::array({i * 0.125, 1.0 - i * 0.25, 3.5}));
  document["widgets"]["lattices"][0]["points"] = points;
  return document.dump();
}

// Whether every object member and array element of `part` is in `whole` (elements in their order,
// some left out), so `part` is `whole` with values dropped.
bool isCutFrom(const Json& part, const Json& whole) {
  if (part.is_object()) {
    if (!whole.is_object()) return false;
    for (auto it = part.begin(); it != part.end(); ++it)
      if (!whole.contains(it.key()) || !isCutFrom(it.value(), whole[it.key()])) return false;
    return true;
  }
  if (part.is_array()) {
    if (!whole.is_array()) return false;
    std::size_t next = 0;
    for (const Json& element : part) {
      while (next < whole.size() && !isCutFrom(element, whole[next])) ++next;
      if (next == whole.size()) return false;
      ++next;
    }
    return true;
  }
  return part == whole;
}

TEST(JsonMutator, ShrinkCutsALongDocumentToFitByDroppingValues) {
  const std::string text = longScene();
  const Json whole = Json::parse(text);
  ASSERT_GT(text.size(), 1200u);
  for (std::size_t maxSize : {800u, 300u, 100u}) {
    std::set<std::string> texts;
    for (std::uint64_t seed = 0; seed < 100; ++seed) {
      const auto shrunk = shrinkJson(text, seed, maxSize);
      ASSERT_TRUE(shrunk) << "seed " << seed << ", " << maxSize << " bytes";
      EXPECT_EQ(shrunk, shrinkJson(text, seed, maxSize)) << "deterministic per seed";
      EXPECT_LE(shrunk->size(), maxSize);
      const Json part = Json::parse(*shrunk, nullptr, false);
      ASSERT_FALSE(part.is_discarded()) << *shrunk;
      EXPECT_TRUE(isCutFrom(part, whole)) << *shrunk;
      texts.insert(*shrunk);
    }
    if (maxSize == 800) {
      EXPECT_GT(texts.size(), 20u) << "the seed chooses what is dropped";
    }
  }
  // A cut of 100 bytes mostly drops a few points, not the widgets.
  int keptMost = 0;
  for (std::uint64_t seed = 0; seed < 100; ++seed)
    if (shrinkJson(text, seed, text.size() - 100)->size() > text.size() / 2) ++keptMost;
  EXPECT_GT(keptMost, 80);
}

TEST(JsonMutator, ShrinkLeavesWhatFitsOrCannotBeCut) {
  EXPECT_FALSE(shrinkJson(kScene, 1, 1000)) << "fits already";
  EXPECT_FALSE(shrinkJson("{\"a\": [1, 2", 1, 5)) << "not JSON";
  EXPECT_FALSE(shrinkJson("\"" + std::string(100, 'x') + "\"", 1, 50)) << "a root string";
  EXPECT_EQ(shrinkJson(R"({"a":[1,2,3],"b":"long text"})", 1, 2), "{}");
}

TEST(JsonMutatorArena, AllocatesOnlyInsideACall) {
  EXPECT_THROW(Arena::current(), std::logic_error);
  {
    const Arena::Scope call;
    std::vector<int, ArenaAllocator<int>> numbers(1000, 7);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(numbers.data()) % alignof(int), 0u);
    {
      const Arena::Scope inner;  // a nested scope does not empty the arena
    }
    std::vector<int, ArenaAllocator<int>> more(1000, 8);
    EXPECT_TRUE(std::all_of(numbers.begin(), numbers.end(), [](int n) { return n == 7; }));
    EXPECT_TRUE(more.data() >= numbers.data() + numbers.size() || more.data() + more.size() <= numbers.data());
  }
  EXPECT_THROW(Arena::current(), std::logic_error);
}

TEST(JsonMutatorArena, ReusesItsMemoryFromCallToCallAndGrowsForLargeValues) {
  void* first = nullptr;
  {
    const Arena::Scope call;
    first = Arena::current().allocate(100, 8);
  }
  {
    const Arena::Scope call;
    EXPECT_EQ(Arena::current().allocate(100, 8), first) << "emptied when the call returned";
    // More than the first block holds, in pieces and at once; every byte writable and kept.
    std::vector<char*> pieces;
    for (int i = 0; i < 64; ++i) {
      pieces.push_back(static_cast<char*>(Arena::current().allocate(64 << 10, 1)));
      std::memset(pieces.back(), i, 64 << 10);
    }
    auto* large = static_cast<char*>(Arena::current().allocate(8 << 20, 16));
    std::memset(large, 0x5a, 8 << 20);
    for (int i = 0; i < 64; ++i) EXPECT_EQ(pieces[std::size_t(i)][(64 << 10) - 1], char(i));
    EXPECT_EQ(large[(8 << 20) - 1], char(0x5a));
  }
}

}  // namespace
}  // namespace ffdkit::fuzz
