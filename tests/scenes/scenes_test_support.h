#pragma once

// Helpers the scenes tests share, each defined once. The test programs are unity builds (several
// test files compiled as one translation unit, tests/CMakeLists.txt), so two files of one program
// may not each define a helper of the same name in their anonymous namespaces.

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "ffdkit/scenes/primitive.h"
#include "ffdkit/scenes/scene.h"

namespace ffdkit::scenes::test_support {

/// The sample scenes (scenes/examples/<name>/scene.json).
inline const std::filesystem::path kExamples = FFDKIT_SOURCE_DIR "/scenes/examples";

/// The bytes of a file ("" if it cannot be read).
inline std::string fileText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// A primitive sphere object named `name`, its mesh built.
inline SceneObject sphereObject(const std::string& name, int resolution = 12) {
  SceneObject object;
  object.name = name;
  object.source = PrimitiveOptions{.kind = PrimitiveKind::Sphere, .resolution = resolution};
  object.mesh = buildObjectMesh(object.source, ".");
  return object;
}

}  // namespace ffdkit::scenes::test_support
