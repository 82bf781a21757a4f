#include "ffdkit/scenes/scene_file.h"
#include "scenes_test_support.h"

#include <fstream>
#include <sstream>

#include <unistd.h>

#include <gtest/gtest.h>

namespace ffdkit::scenes {
namespace {
using test_support::kExamples;
using test_support::fileText;

constexpr const char* kSamples[] = {"default", "press", "vise", "mirror", "hierarchy", "cylinder-twist"};

// Message of the SceneFileError that reading `text` raises ("" if none).
std::string sceneErrorOf(const std::string& text) {
  std::istringstream in(text);
  try {
    readScene(in, "scene.json");
  } catch (const SceneFileError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneFile, EverySampleRoundTripsByteForByte) {
  for (const char* name : kSamples) {
    SCOPED_TRACE(name);
    const auto path = kExamples / name / "scene.json";
    const Scene scene = readScene(kExamples / name);
    EXPECT_EQ(sceneFileText(scene), fileText(path));
  }
}

TEST(SceneFile, AStreamIsReadWholeHoweverLongAndWhereverItEnds) {
  // The reader takes a stream in blocks of 16 KiB: a scene several blocks long (a long
  // description) reads whole, as does one that ends exactly at a block's end or a byte after it.
  const std::string sample = fileText(kExamples / "press" / "scene.json");
  const Scene expected = readScene(kExamples / "press");
  const std::string key = "\"description\": \"";
  const std::size_t from = sample.find(key) + key.size();
  const std::size_t to = sample.find('"', from);
  ASSERT_LT(to, sample.size());
  for (const std::size_t length : {std::size_t(1), std::size_t(70000)}) {
    const std::string description(length, 'd');
    const std::string text = sample.substr(0, from) + description + sample.substr(to);
    for (const std::size_t padding : {std::size_t(0), std::size_t(1), 16384 - text.size() % 16384}) {
      SCOPED_TRACE(std::to_string(length) + " + " + std::to_string(padding));
      const std::string padded = text + std::string(padding, ' ');
      std::istringstream in(padded);
      const Scene scene = readScene(in, "scene.json");
      EXPECT_EQ(scene.description, description);
      ASSERT_EQ(scene.objects().size(), expected.objects().size());
      EXPECT_EQ(scene.objects()[0].mesh.points, expected.objects()[0].mesh.points);
    }
  }
}

TEST(SceneFile, LoadingReproducesControlPointsAndObjects) {
  for (const char* name : kSamples) {
    SCOPED_TRACE(name);
    const Scene scene = readScene(kExamples / name);
    std::istringstream again(sceneFileText(scene));
    const Scene copy = readScene(again, "copy", {.baseDirectory = kExamples / name});
    ASSERT_EQ(copy.objects().size(), scene.objects().size());
    for (std::size_t o = 0; o < scene.objects().size(); ++o) EXPECT_EQ(copy.objects()[o].mesh.points, scene.objects()[o].mesh.points);
    for (auto lattice : scene.widgets.widgets(widgets::WidgetType::Lattice))
      EXPECT_EQ(copy.widgets.worldControlPoints(copy.widgets.find(scene.widgets.name(lattice))),
                scene.widgets.worldControlPoints(lattice));
  }
}

TEST(SceneFile, MeshFilesAndWidgetFilesResolveNextToTheScene) {
  const auto dir = std::filesystem::temp_directory_path() / "ffdkit-scene-file-test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "meshes");
  std::ofstream(dir / "meshes" / "cloud.xyz") << "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  Scene scene = readScene(kExamples / "default");
  SceneObject cloud;
  cloud.name = "cloud";
  cloud.source = MeshFileSource{"meshes/cloud.xyz"};
  cloud.mesh = buildObjectMesh(cloud.source, dir);
  scene.addObject(cloud);
  scene.widgetFile = "tool.widgets.json";
  writeScene(dir / "scene.json", scene);
  EXPECT_TRUE(std::filesystem::exists(dir / "tool.widgets.json"));
  const Scene back = readScene(dir / "scene.json");
  EXPECT_EQ(back.findObject("cloud")->mesh.points.rows(), 4);
  EXPECT_EQ(sceneFileText(back), fileText(dir / "scene.json"));

  // A missing mesh file is named, with the scene that references it.
  std::filesystem::remove(dir / "meshes" / "cloud.xyz");
  try {
    readScene(dir / "scene.json");
    FAIL() << "expected an error";
  } catch (const SceneFileError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("scene.json /objects/1"), std::string::npos) << message;
    EXPECT_NE(message.find("cloud.xyz: no such file"), std::string::npos) << message;
  }
  std::filesystem::remove_all(dir);
}

TEST(SceneFile, MeshPathsOutsideTheScenesFolderAreRefusedUnlessAllowed) {
  const auto root = std::filesystem::temp_directory_path() / ("ffdkit-scene-paths-" + std::to_string(::getpid()));
  std::filesystem::remove_all(root);
  std::filesystem::create_directories(root / "shared" / "meshes");
  std::ofstream(root / "secret.xyz") << "0 0 0\n";
  std::ofstream(root / "shared" / "meshes" / "ok.xyz") << "0 0 0\n1 1 1\n";
  std::filesystem::create_symlink(root / "secret.xyz", root / "shared" / "link.xyz");
  auto sceneWith = [&](const std::string& path) {
    std::ofstream(root / "shared" / "scene.json")
        << R"({"format": "ffdkit-scene", "version": 1, "objects": [{"name": "m", "mesh": {"path": ")" << path << R"("}}]})";
  };
  for (const std::string& path : std::vector<std::string>{"../secret.xyz", (root / "secret.xyz").string(), "meshes/../../secret.xyz", "link.xyz"}) {
    SCOPED_TRACE(path);
    sceneWith(path);
    try {
      readScene(root / "shared" / "scene.json");
      ADD_FAILURE() << "expected an error";
    } catch (const SceneFileError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("scene.json /objects/0/mesh/path: object 'm': mesh file '" + path +
                             "' is outside the folder of the file that names it"),
                std::string::npos)
          << message;
    }
    SceneReadOptions allow;
    allow.confinement.allowOutside = true;
    EXPECT_EQ(readScene(root / "shared" / "scene.json", allow).objects()[0].mesh.points.rows(), 1);
  }
  for (const std::string& path : std::vector<std::string>{"meshes/ok.xyz", (root / "shared" / "meshes" / "ok.xyz").string(), "meshes/../meshes/ok.xyz"}) {
    SCOPED_TRACE(path);
    sceneWith(path);
    EXPECT_EQ(readScene(root / "shared" / "scene.json").objects()[0].mesh.points.rows(), 2);
  }
  std::filesystem::remove_all(root);
}

TEST(SceneFile, BadInputGetsLocatedErrors) {
  const std::string base = fileText(kExamples / "default" / "scene.json");
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string text = base;
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  EXPECT_NE(sceneErrorOf("{\n  \"format\": \"ffdkit-scene\",\n  \"version\": 1,,\n}").find("scene.json:3:"), std::string::npos);
  EXPECT_NE(sceneErrorOf(replaced("\"version\": 2", "\"version\": 7")).find("/version: format version 7 is not supported"),
            std::string::npos);
  EXPECT_NE(sceneErrorOf(replaced("\"kind\": \"sphere\"", "\"kind\": \"teapot\"")).find("/objects/0/primitive/kind: unknown primitive 'teapot'"),
            std::string::npos);
  EXPECT_NE(sceneErrorOf(replaced("\"resolution\": 48", "\"resolution\": 100000")).find("/objects/0/primitive/resolution"),
            std::string::npos);
  EXPECT_NE(sceneErrorOf(replaced("\"size\": 1.0", "\"size\": 1.0, \"colour\": 3")).find("unknown key 'colour'"), std::string::npos);
  // The file names the lattice; an unknown name is an error at its key (the scene holds ids).
  EXPECT_NE(sceneErrorOf(replaced("\"lattice\": \"lattice\"", "\"lattice\": \"nope\"")).find("/attachments/0/lattice: attachment of 'nope'"),
            std::string::npos);
  EXPECT_NE(sceneErrorOf(replaced("\"lattice\": \"lattice\"", "\"lattice\": \"top\"")).find("/attachments: scene: attachment names 'top', which is not a lattice widget"),
            std::string::npos);
  EXPECT_NE(sceneErrorOf(replaced("\"objects\": [\"sphere\"]", "\"objects\": [\"moon\"]")).find("unknown object 'moon'"),
            std::string::npos);
  EXPECT_NE(sceneErrorOf(replaced("\"primitive\": {", "\"generator\": {\"name\": \"nope\"}, \"primitive\": {")).find("exactly one"),
            std::string::npos);
  EXPECT_NE(sceneErrorOf(replaced("\"counts\": [3, 3, 3]", "\"counts\": [1, 3, 3]")).find("/widgets"), std::string::npos);
  EXPECT_NE(sceneErrorOf(replaced("\"position\": [3.0, -3.8, 2.7]", "\"position\": [0.0, 0.0, 0.3]")).find("/camera"),
            std::string::npos);
}

TEST(SceneFile, CurveStyleRoundTripsAndTheDefaultIsNotWritten) {
  Scene scene = readScene(kExamples / "default");
  EXPECT_EQ(scene.objects().front().display.curveStyle, CurveStyle::Tube);
  EXPECT_EQ(sceneFileText(scene).find("curveStyle"), std::string::npos);  // older files keep their bytes

  DisplaySettings look = scene.objects().front().display;
  look.curveStyle = CurveStyle::Line;
  scene.setObjectDisplay(scene.objects().front().name, look);
  const std::string text = sceneFileText(scene);
  EXPECT_NE(text.find("\"curveStyle\": \"line\""), std::string::npos) << text;
  std::istringstream in(text);
  const Scene back = readScene(in, "scene.json", {.baseDirectory = kExamples / "default"});
  EXPECT_EQ(back.objects().front().display.curveStyle, CurveStyle::Line);
  EXPECT_EQ(back.objects().front().display, scene.objects().front().display);
  EXPECT_EQ(sceneFileText(back), text);

  // "tube" spelled out reads as the default and is then omitted again.
  std::string tube = text;
  tube.replace(tube.find("\"line\""), 6, "\"tube\"");
  std::istringstream tubeIn(tube);
  const Scene tubeScene = readScene(tubeIn, "scene.json", {.baseDirectory = kExamples / "default"});
  EXPECT_EQ(tubeScene.objects().front().display.curveStyle, CurveStyle::Tube);
  EXPECT_EQ(sceneFileText(tubeScene).find("curveStyle"), std::string::npos);
}

TEST(SceneFile, AnUnknownCurveStyleIsRefusedWithItsPlaceAndTheKnownStyles) {
  const std::string base = fileText(kExamples / "default" / "scene.json");
  const std::string anchor = "\"visible\": true";
  auto with = [&](const std::string& extra) {
    std::string text = base;
    const auto at = text.find(anchor);
    EXPECT_NE(at, std::string::npos);
    return text.replace(at, anchor.size(), anchor + ", " + extra);
  };
  const std::string message = sceneErrorOf(with("\"curveStyle\": \"ribbon\""));
  EXPECT_NE(message.find("scene.json /objects/0/display/curveStyle: unknown curve style 'ribbon' (known: tube, line)"),
            std::string::npos)
      << message;
  EXPECT_NE(sceneErrorOf(with("\"curveStyle\": 1")).find("/objects/0/display/curveStyle"), std::string::npos);
  EXPECT_EQ(sceneErrorOf(with("\"curveStyle\": \"line\"")), "");  // the splice itself is fine
}

TEST(SceneFile, AFailedWriteLeavesTheOldFile) {
  const auto dir = std::filesystem::temp_directory_path() / "ffdkit-scene-write-test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const Scene scene = readScene(kExamples / "default");
  writeScene(dir / "scene.json", scene);
  const std::string before = fileText(dir / "scene.json");
  EXPECT_THROW(writeScene(dir / "missing-folder" / "scene.json", scene), SceneFileError);
  EXPECT_EQ(fileText(dir / "scene.json"), before);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ffdkit::scenes
