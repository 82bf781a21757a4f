// Hostile scene and widget files: what a file can make the reader allocate is charged to one
// budget before it is allocated, every path a scene names is confined to its folder, and every
// integer field follows one rule. Each case is a small file an attacker could send.
#include <chrono>
#include <cstdint>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "ffdkit/scenes/generator.h"
#include "ffdkit/scenes/primitive.h"
#include "ffdkit/scenes/scene_file.h"
#include "ffdkit/scenes/widget_file.h"
#include "scenes_test_support.h"

namespace ffdkit::scenes {
namespace {
using test_support::kExamples;
using test_support::contains;

namespace fs = std::filesystem;

// The what() of the SceneFileError reading `text` raises ("" when it reads).
std::string sceneError(const std::string& text, const SceneReadOptions& options = {}) {
  std::istringstream in(text);
  try {
    readScene(in, "scene.json", options);
  } catch (const SceneFileError& e) {
    return e.what();
  }
  return "";
}

std::string widgetError(const std::string& text, const WidgetReadOptions& options = {}) {
  std::istringstream in(text);
  try {
    readWidgetFile(in, "tool.json", options);
  } catch (const WidgetFileError& e) {
    return e.what();
  }
  return "";
}

// `count` copies of `item`, comma-separated: the elements of a big JSON array.
std::string commaSeparated(int count, const std::string& item) {
  std::string text;
  for (int i = 0; i < count; ++i) text += i ? "," + item : item;
  return text;
}

// A widget file with no lattices whose "cells" member is `cells`, followed by `end`.
std::string toolWithCells(const std::string& cells, const std::string& end = "}") {
  return R"({"format": "ffdkit-widgets", "version": 1, "lattices": [], "cells": )" + cells + end;
}

// A scene of the given objects (JSON object texts), version 2.
std::string sceneOf(const std::vector<std::string>& objects, const std::string& extra = "") {
  std::string list;
  for (const auto& o : objects) list += (list.empty() ? "" : ", ") + o;
  return R"({"format": "ffdkit-scene", "version": 2, "objects": [)" + list + "]" + extra + "}";
}

std::string sphereJson(const std::string& name, int resolution) {
  return R"({"name": ")" + name + R"(", "primitive": {"kind": "sphere", "resolution": )" + std::to_string(resolution) + "}}";
}

// A folder of its own under the temporary directory, removed at the end of the test.
struct HostileFolder {
  fs::path root;
  explicit HostileFolder(const std::string& name)
      : root(fs::temp_directory_path() / ("ffdkit-hostile-" + name + "-" + std::to_string(::getpid()))) {
    fs::remove_all(root);
    fs::create_directories(root);
  }
  ~HostileFolder() { fs::remove_all(root); }
  void write(const fs::path& relative, const std::string& text) const {
    fs::create_directories((root / relative).parent_path());
    std::ofstream(root / relative, std::ios::binary) << text;
  }
};

// ---- amplification ------------------------------------------------------------------------

TEST(HostileWidgetFile, ATinyFileAskingForAHugeLatticeIsALocatedErrorBeforeAnyAllocation) {
  const std::string tool =
      R"({"format": "ffdkit-widgets", "version": 1, "lattices": [{"id": "w0", "name": "box", "counts": [1000, 1000, 100]}]})";
  ASSERT_LE(tool.size(), 200u);
  const std::string e = widgetError(tool);
  EXPECT_TRUE(contains(e, "tool.json /lattices/0/counts: lattice 'box' asks for 1000 x 1000 x 100 = 100000000 control points"))
      << e;
  EXPECT_TRUE(contains(e, "over the read limit of 50000000 points (--max-points)")) << e;
}

TEST(HostileWidgetFile, ALatticeBeyondWhatAModelHoldsIsRefusedWhateverTheLimits) {
  WidgetReadOptions unlimited;
  unlimited.limits.maxPoints = std::uint64_t(1) << 62;
  unlimited.limits.maxMemoryBytes = std::uint64_t(1) << 62;
  const std::string e = widgetError(
      R"({"format": "ffdkit-widgets", "version": 1, "lattices": [{"id": "w0", "name": "box", "counts": [1000000, 1000000, 1000]}]})",
      unlimited);
  EXPECT_TRUE(contains(e, "tool.json /lattices/0/counts: lattice 'box' asks for 1000000 x 1000000 x 1000 = 1000000000000000 "
                          "control points, more than a lattice holds (100000000)"))
      << e;
}

TEST(HostileWidgetFile, ALatticeExactlyAtThePointLimitReadsAndOneOverIsRefused) {
  const std::string tool =
      R"({"format": "ffdkit-widgets", "version": 1, "lattices": [{"id": "w0", "name": "box", "counts": [3, 4, 5]}]})";
  WidgetReadOptions options;
  options.limits.maxPoints = 60;
  meshio::ReadBudget budget(options.limits);
  options.budget = &budget;
  std::istringstream in(tool);
  const widgets::WidgetModel model = readWidgetFile(in, "tool.json", options);
  EXPECT_EQ(model.controlPoints(model.find("box")).rows(), 60);
  EXPECT_EQ(budget.pointsCharged(), 60u);
  options.budget = nullptr;
  options.limits.maxPoints = 59;
  const std::string e = widgetError(tool, options);
  EXPECT_TRUE(contains(e, "/lattices/0/counts: lattice 'box' asks for 3 x 4 x 5 = 60 control points")) << e;
  EXPECT_TRUE(contains(e, "over the read limit of 59 points")) << e;
}

TEST(HostileWidgetFile, ACompactDocumentIsChargedBeforeItIsParsed) {
  // "[0,0,0,...]" makes a document about ten times its text: the read charges it first.
  const std::string tool = toolWithCells("[" + commaSeparated(100000, "0") + "]");
  WidgetReadOptions options;
  options.limits.maxMemoryBytes = 10 * tool.size();
  const std::string e = widgetError(tool, options);
  EXPECT_TRUE(contains(e, "tool.json: the parsed JSON of " + std::to_string(tool.size()) + " bytes")) << e;
  EXPECT_TRUE(contains(e, "(--max-memory)")) << e;
}

// The parsed-JSON charge a refusal names: "... bytes: 1 items of N bytes need ...".
std::string chargedDocumentBytes(const std::string& error) {
  const std::string marker = "1 items of ";
  const std::size_t at = error.find(marker);
  if (at == std::string::npos) return "";
  return error.substr(at + marker.size(), error.find(' ', at + marker.size()) - at - marker.size());
}

TEST(HostileWidgetFile, ADocumentOverTheLimitIsRefusedWithItsWholeSizeHoweverEarlyTheBuildStops) {
  // The document is charged as it is built: past the limit the build stops and the rest of the
  // text is only counted, so the refusal names the same size whether the limit is just under it
  // or a small fraction of it.
  const std::string tool = toolWithCells("[" + commaSeparated(20000, "[0.5,1]") + "]");
  WidgetReadOptions options;
  options.limits.maxMemoryBytes = tool.size() + 1000;  // the text is charged first, then its document
  const std::string early = widgetError(tool, options);
  const std::string size = chargedDocumentBytes(early);
  ASSERT_FALSE(size.empty()) << early;
  // Each pair is a value and a container with two values: 20,000 x (32 + 64 + 2 x 32) bytes at least.
  EXPECT_GT(std::stoull(size), 20000ull * 160ull) << early;
  options.limits.maxMemoryBytes = tool.size() + std::stoull(size) - 1;
  const std::string late = widgetError(tool, options);
  EXPECT_EQ(chargedDocumentBytes(late), size) << late;
  EXPECT_TRUE(contains(late, "tool.json: the parsed JSON of " + std::to_string(tool.size()) + " bytes")) << late;
}

TEST(HostileWidgetFile, ADocumentExactlyAtTheLimitReadsAndOneByteLessIsRefused) {
  const std::string tool =
      R"({"format": "ffdkit-widgets", "version": 1, "lattices": [], "cells": [], "affines": [], "rootOrder": []})";
  WidgetReadOptions options;
  meshio::ReadBudget budget(options.limits);
  options.budget = &budget;
  std::istringstream in(tool);
  ASSERT_NO_THROW(readWidgetFile(in, "tool.json", options));
  // Nothing else in this file is charged: the text and its document are the whole read.
  const std::uint64_t charged = budget.bytesCharged();
  options.budget = nullptr;
  options.limits.maxMemoryBytes = charged;
  EXPECT_EQ(widgetError(tool, options), "");
  options.limits.maxMemoryBytes = charged - 1;
  const std::string e = widgetError(tool, options);
  EXPECT_TRUE(contains(e, "tool.json: the parsed JSON of " + std::to_string(tool.size()) + " bytes: 1 items of " +
                              std::to_string(charged - tool.size()) + " bytes"))
      << e;
}

TEST(HostileWidgetFile, ASyntaxErrorAfterTheLimitIsTheLimitAndOneWithinItIsTheSyntaxError) {
  // The document up to the error is what the read would have built: over the limit, the limit is
  // the error; within it, the syntax error at its line and column.
  const std::string tool = toolWithCells("[" + commaSeparated(5000, "0"), ",}");  // an unfinished array
  WidgetReadOptions options;
  options.limits.maxMemoryBytes = 2 * tool.size();
  const std::string over = widgetError(tool, options);
  EXPECT_TRUE(contains(over, "tool.json: the parsed JSON of " + std::to_string(tool.size()) + " bytes")) << over;
  EXPECT_FALSE(contains(over, "syntax error")) << over;
  const std::string within = widgetError(tool, {});
  EXPECT_TRUE(contains(within, "tool.json:1:" + std::to_string(tool.size()) + ": syntax error")) << within;
}

TEST(HostileScene, EightMaximumResolutionSpheresFailAtTheObjectThatCrossesTheLimit) {
  // Each sphere at resolution 4096 is charged 4097 x 2049 vertices (its grid before the poles
  // and the seam are welded): five fit in the default 50M points, the sixth does not. The
  // primitives are counted before any is built, so the read fails at once.
  const std::uint64_t each = 4097ull * 2049ull;
  ASSERT_EQ(primitiveSize({.kind = PrimitiveKind::Sphere, .resolution = 4096}).vertices, each);
  std::vector<std::string> spheres;
  for (int i = 0; i < 8; ++i) spheres.push_back(sphereJson("s" + std::to_string(i), 4096));
  const auto start = std::chrono::steady_clock::now();
  const std::string e = sceneError(sceneOf(spheres));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  EXPECT_EQ(e, "scene.json /objects/5: object 's5': primitive sphere at resolution 4096: up to 8394753 vertices: 8394753 points; "
               "with the 41973765 this read holds already that is over the read limit of 50000000 points (--max-points)");
}

TEST(HostileScene, PrimitivesAreCountedBeforeAnyIsBuiltAndAgainAsTheyAreBuilt) {
  // Six small spheres and a limit of five and a half: the count before building refuses the
  // sixth; with a mesh-free scene under the limit everything reads and the points add up.
  const std::uint64_t small = primitiveSize({.kind = PrimitiveKind::Sphere, .resolution = 16}).vertices;
  std::vector<std::string> spheres;
  for (int i = 0; i < 6; ++i) spheres.push_back(sphereJson("s" + std::to_string(i), 16));
  SceneReadOptions options;
  options.limits.maxPoints = 5 * small + small / 2;
  const std::string e = sceneError(sceneOf(spheres), options);
  EXPECT_TRUE(contains(e, "scene.json /objects/5: object 's5': primitive sphere at resolution 16: up to " + std::to_string(small) +
                              " vertices: " + std::to_string(small) + " points; with the " + std::to_string(5 * small) +
                              " this read holds already"))
      << e;
  spheres.pop_back();
  std::istringstream in(sceneOf(spheres));
  const Scene scene = readScene(in, "scene.json", options);
  ASSERT_EQ(scene.objects().size(), 5u);
  // Welding the seam and the poles leaves fewer vertices than the grid the budget counts.
  EXPECT_LE(std::uint64_t(scene.objects()[0].mesh.points.rows()), small);
}

TEST(HostileScene, APrimitiveExactlyAtThePointLimitReadsAndOneOverIsRefused) {
  // A plane's grid has no seams: (n + 1)^2 vertices exactly.
  const std::string scene = sceneOf({R"({"name": "p", "primitive": {"kind": "plane", "resolution": 10}})"});
  SceneReadOptions options;
  options.limits.maxPoints = 121;
  std::istringstream in(scene);
  EXPECT_EQ(readScene(in, "scene.json", options).objects()[0].mesh.points.rows(), 121);
  options.limits.maxPoints = 120;
  const std::string e = sceneError(scene, options);
  EXPECT_TRUE(contains(e, "scene.json /objects/0: object 'p': primitive plane at resolution 10: up to 121 vertices")) << e;
}

TEST(HostileScene, OneBudgetCoversObjectsAndTheWidgetsTogether) {
  // 121 points of a plane and 8 of a lattice: 129 fit, 128 do not, and the lattice is named.
  const std::string widgets =
      R"(, "widgets": {"format": "ffdkit-widgets", "version": 1, "lattices": [{"id": "w0", "name": "box", "counts": [2, 2, 2]}]})";
  const std::string scene = sceneOf({R"({"name": "p", "primitive": {"kind": "plane", "resolution": 10}})"}, widgets);
  SceneReadOptions options;
  options.limits.maxPoints = 129;
  EXPECT_EQ(sceneError(scene, options), "");
  options.limits.maxPoints = 128;
  const std::string e = sceneError(scene, options);
  EXPECT_TRUE(contains(e, "scene.json /widgets/lattices/0/counts: lattice 'box' asks for 2 x 2 x 2 = 8 control points")) << e;
  EXPECT_TRUE(contains(e, "with the 121 this read holds already")) << e;
}

TEST(HostileScene, AGeneratorIsChargedItsSamplesBeforeItRuns) {
  const std::string scene = sceneOf({R"({"name": "c", "generator": {"name": "qi-interpolate", "parameters":
      {"points": [[0, 0, 0], [1, 0, 0], [1, 1, 0]], "samples": 100000000}}})"});
  const std::string e = sceneError(scene);
  EXPECT_TRUE(contains(e, "scene.json /objects/0: object 'c': generator 'qi-interpolate': up to 100000000 points")) << e;
  EXPECT_TRUE(contains(e, "over the read limit of 50000000 points (--max-points)")) << e;
}

TEST(HostileScene, EveryGeneratorsBoundHoldsEveryGeneratedSampleAtSeveralDensities) {
  // The bound is charged instead of the points: it must not be below them, and not so far above
  // that a scene the machine can hold is refused.
  const GeneratorRegistry& registry = builtinGenerators();
  for (const std::string& name : registry.names()) ASSERT_TRUE(static_cast<bool>(registry.get(name).pointBound)) << name;
  std::set<std::string> covered;
  for (const auto& entry : fs::directory_iterator(kExamples)) {
    if (!fs::exists(entry.path() / "scene.json")) continue;
    const Scene sample = readScene(entry.path());
    for (const SceneObject& object : sample.objects()) {
      const auto* source = std::get_if<GeneratedSource>(&object.source);
      if (source == nullptr) continue;
      SCOPED_TRACE(entry.path().filename().string() + " " + object.name);
      covered.insert(source->generator);
      for (double density : {0.5, 1.0, 3.0}) {
        SCOPED_TRACE(density);
        const auto points = std::uint64_t(registry.generate(source->generator, source->parameters, density).points.rows());
        const std::uint64_t bound = registry.get(source->generator).pointBound(source->parameters, density);
        EXPECT_GE(bound, points);
        EXPECT_LE(bound, 4 * points + 64);
      }
    }
  }
  const std::vector<std::string> names = registry.names();
  EXPECT_EQ(std::vector<std::string>(covered.begin(), covered.end()), names);
}

TEST(HostileScene, AFailedAllocationBecomesASceneFileError) {
#ifdef FFDKIT_ASAN
  GTEST_SKIP() << "AddressSanitizer reports an allocation this large itself instead of failing it";
#endif
  // With the limits lifted, a sigma-spline surface sampled 10^8 x 10^8 per span asks Eigen for
  // 4 x 10^16 vertices at once: std::bad_alloc, before anything is filled. It must leave the
  // reader as its documented error.
  SceneReadOptions unlimited;
  unlimited.limits.maxPoints = std::numeric_limits<std::uint64_t>::max();
  unlimited.limits.maxMemoryBytes = std::numeric_limits<std::uint64_t>::max();
  const std::string e = sceneError(sceneOf({R"({"name": "s", "generator": {"name": "sigma-spline-surface", "parameters": {
      "points": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], "columns": 2,
      "samples-per-span-u": 100000000, "samples-per-span-v": 100000000}}})"}),
                                   unlimited);
  EXPECT_TRUE(contains(e, "scene.json /objects/0: object 's': generator 'sigma-spline-surface': out of memory while generating")) << e;
}

// ---- confinement --------------------------------------------------------------------------

TEST(HostileScene, AWidgetFileOutsideTheScenesFolderIsRefusedWithoutQuotingIt) {
  const HostileFolder folder("widget-path");
  const std::string marker = "PRIVATE-MARKER-5c1e";
  // A valid widget file outside, whose lattice name is the marker, and an invalid one that holds
  // the marker where a syntax error would quote it.
  folder.write("private/tool.json", R"({"format": "ffdkit-widgets", "version": 1, "lattices": [{"id": "w0", "name": ")" +
                                        marker + R"(", "counts": [2, 2, 2]}]})");
  folder.write("private/broken.json", "{\"format\": " + marker + "}");
  fs::create_directories(folder.root / "shared");
  fs::create_symlink(folder.root / "private" / "tool.json", folder.root / "shared" / "link.json");
  auto sceneNaming = [&](const std::string& path) {
    folder.write("shared/scene.json", sceneOf({}, R"(, "widgetFile": ")" + path + "\""));
  };
  const std::vector<std::string> outside = {"../private/tool.json", (folder.root / "private" / "tool.json").string(), "link.json"};
  for (const std::string& path : outside) {
    SCOPED_TRACE(path);
    sceneNaming(path);
    try {
      readScene(folder.root / "shared" / "scene.json");
      ADD_FAILURE() << "expected an error";
    } catch (const SceneFileError& e) {
      const std::string message = e.what();
      EXPECT_TRUE(contains(message, "scene.json /widgetFile: widget file '" + path + "' is outside the folder of the file that names it"))
          << message;
      EXPECT_TRUE(contains(message, "--allow-outside")) << message;
      EXPECT_FALSE(contains(message, marker)) << message;
    }
    SceneReadOptions allow;
    allow.confinement.allowOutside = true;
    const Scene scene = readScene(folder.root / "shared" / "scene.json", allow);
    EXPECT_TRUE(scene.widgets.contains(scene.widgets.find(marker)));
  }
  // Allowed outside, a syntax error still names the place and not the bytes.
  sceneNaming("../private/broken.json");
  SceneReadOptions allow;
  allow.confinement.allowOutside = true;
  try {
    readScene(folder.root / "shared" / "scene.json", allow);
    ADD_FAILURE() << "expected an error";
  } catch (const SceneFileError& e) {
    const std::string message = e.what();
    EXPECT_TRUE(contains(message, "broken.json:1:")) << message;
    EXPECT_TRUE(contains(message, "syntax error")) << message;
    EXPECT_FALSE(contains(message, marker)) << message;
  }
  // Inside the folder a widget file reads by default.
  folder.write("shared/tools/tool.json",
               R"({"format": "ffdkit-widgets", "version": 1, "lattices": [{"id": "w0", "name": "inside", "counts": [2, 2, 2]}]})");
  sceneNaming("tools/../tools/tool.json");
  EXPECT_NO_THROW(readScene(folder.root / "shared" / "scene.json"));
}

TEST(HostileScene, AMeshOutsideTheScenesFolderIsRefusedWithoutQuotingIt) {
  const HostileFolder folder("mesh-path");
  const std::string marker = "PRIVATE-MARKER-9d2b";
  folder.write("private/points.xyz", "0 0 0 " + marker + "\n");
  folder.write("shared/scene.json", sceneOf({R"({"name": "m", "mesh": {"path": "../private/points.xyz"}})"}));
  try {
    readScene(folder.root / "shared" / "scene.json");
    ADD_FAILURE() << "expected an error";
  } catch (const SceneFileError& e) {
    const std::string message = e.what();
    EXPECT_TRUE(contains(message, "scene.json /objects/0/mesh/path: object 'm': mesh file '../private/points.xyz' is outside the "
                                  "folder of the file that names it"))
        << message;
    EXPECT_FALSE(contains(message, marker)) << message;
  }
}

// ---- integers -----------------------------------------------------------------------------

TEST(HostileScene, TheSmallestInt64FrameIsRefusedNotWrapped) {
  const std::string e = sceneError(sceneOf({}, R"(, "animation": {"frames": [-9223372036854775808, 5]})"));
  EXPECT_TRUE(contains(e, "scene.json /animation/frames/0: expected an integer in [-10000000, 10000000], got -9223372036854775808"))
      << e;
}

struct IntegerField {
  std::string file;      // "scene" or "widget"
  std::string text;      // the document with @ where the value goes
  std::string pointer;   // where the error must point
  std::string range;     // "[lo, hi]" as the message gives it
  std::string negative;  // a value below the range
  bool numberParameter = false;  // a generator parameter: held as a number, so 2.0 is the integer 2
};

TEST(HostileScene, EveryIntegerFieldRefusesFractionsValuesOutOfRangeAndHugeNumbers) {
  const std::string lattice = R"({"id": "w0", "name": "box", "counts": [3, 3, 3]})";
  const std::string widgetHead = R"({"format": "ffdkit-widgets", "version": 1, "lattices": [)";
  const std::vector<IntegerField> fields = {
      {"scene", R"({"format": "ffdkit-scene", "version": @, "objects": []})", "/version", "[1, 2147483647]", "-1"},
      {"scene", sceneOf({R"({"name": "p", "primitive": {"kind": "plane", "resolution": @}})"}), "/objects/0/primitive/resolution",
       "[3, 4096]", "-1"},
      {"scene", sceneOf({R"({"name": "p", "primitive": {"kind": "plane", "resolution": 4}, "display": {"zebraStripes": @}})"}),
       "/objects/0/display/zebraStripes", "[1, 256]", "-1"},
      {"scene", sceneOf({}, R"(, "animation": {"frames": [0, @]})"), "/animation/frames/1", "[-10000000, 10000000]", "-10000001"},
      {"scene", sceneOf({R"({"name": "c", "generator": {"name": "qi-interpolate", "parameters": {"points": [[0, 0, 0], [1, 0, 0]],
           "samples": @}}})"}),
       "/objects/0: object 'c': generator 'qi-interpolate': parameter 'samples'", "[2, 100000000]", "-1", true},
      {"widget", R"({"format": "ffdkit-widgets", "version": @})", "/version", "[1, 2147483647]", "-1"},
      {"widget", widgetHead + R"({"id": "w0", "name": "box", "counts": [@, 3, 3]}]})", "/lattices/0/counts/0", "[2, 1000000]", "-1"},
      {"widget", widgetHead + R"({"id": "w0", "name": "box", "counts": [3, 3, 3], "basis": [{"kind": "bspline", "degree": @},
           {"kind": "bernstein"}, {"kind": "bernstein"}]}]})",
       "/lattices/0/basis/0/degree", "[1, 32]", "-1"},
      {"widget", widgetHead + R"({"id": "w0", "name": "box", "counts": [3, 3, 3], "reembed": {"policy": "every-n", "n": @}}]})",
       "/lattices/0/reembed/n", "[1, 1000000]", "-1"},
      {"widget", widgetHead + lattice + R"(], "cells": [{"id": "w1", "name": "c", "lattice": "w0", "kind": "point", "base": [0, @, 0]}]})",
       "/cells/0/base/1", "[0, 999999]", "-1"},
      {"widget", widgetHead + lattice + R"(], "cells": [{"id": "w1", "name": "c", "lattice": "w0", "kind": "edge", "base": [0, 0, 0], "axis": @}]})",
       "/cells/0/axis", "[0, 2]", "-1"},
      {"widget", widgetHead + lattice + R"(], "cells": [{"id": "w1", "name": "c", "lattice": "w0", "kind": "slab", "axis": 0, "plane": @}]})",
       "/cells/0/plane", "[0, 999999]", "-1"},
      {"widget", widgetHead + lattice + R"(], "cells": [{"id": "w1", "name": "c", "lattice": "w0", "kind": "custom", "indices": [1, @]}]})",
       "/cells/0/indices/1", "[0, 99999999]", "-1"},
  };
  for (const IntegerField& field : fields) {
    SCOPED_TRACE(field.pointer);
    for (const std::string& value : {std::string("5.5"), std::string("2.0"), field.negative, std::string("-9223372036854775808"),
                                     std::string("18446744073709551615"), std::string("1e30")}) {
      SCOPED_TRACE(value);
      if (value == "2.0" && field.numberParameter) continue;
      std::string text = field.text;
      text.replace(text.find('@'), 1, value);
      const std::string e = field.file == "scene" ? sceneError(text) : widgetError(text);
      const std::string source = field.file == "scene" ? "scene.json " : "tool.json ";
      EXPECT_TRUE(contains(e, source + field.pointer)) << e;
      EXPECT_TRUE(contains(e, "expected an integer in " + field.range + ", got ")) << e;
    }
  }
}

}  // namespace
}  // namespace ffdkit::scenes
