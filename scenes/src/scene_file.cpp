#include "ffdkit/scenes/scene_file.h"

#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>

#include <nlohmann/json.hpp>

#include "ffdkit/scenes/atomic_write.h"

namespace ffdkit::scenes {
namespace {

using Json = nlohmann::ordered_json;

// Where in the document a value sits, for error messages: "scene.json /objects/2/name".
struct Location {
  const std::string& source;
  std::string pointer;

  Location operator/(const std::string& key) const { return {source, pointer + "/" + key}; }
  Location operator/(std::size_t index) const { return {source, pointer + "/" + std::to_string(index)}; }
  [[noreturn]] void fail(const std::string& message) const {
    throw SceneFileError(source + " " + (pointer.empty() ? "/" : pointer) + ": " + message);
  }
};

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

const Json& member(const Json& object, const char* key, const Location& at) {
  if (!object.is_object()) at.fail("expected an object");
  auto it = object.find(key);
  if (it == object.end()) at.fail(std::string("missing '") + key + "'");
  return *it;
}

double number(const Json& value, const Location& at) {
  if (!value.is_number()) at.fail("expected a number, got " + value.dump());
  const double x = value.get<double>();
  if (!std::isfinite(x)) at.fail("expected a finite number");
  return x;
}

std::string text(const Json& value, const Location& at) {
  if (!value.is_string()) at.fail("expected a string, got " + value.dump());
  return value.get<std::string>();
}

Eigen::Vector3d vector3(const Json& value, const Location& at) {
  if (!value.is_array() || value.size() != 3) at.fail("expected an array of 3 numbers, got " + value.dump());
  return {number(value[0], at / 0), number(value[1], at / 1), number(value[2], at / 2)};
}

Eigen::Vector3d colour(const Json& value, const Location& at) {
  const Eigen::Vector3d c = vector3(value, at);
  if ((c.array() < 0.0).any() || (c.array() > 1.0).any()) at.fail("colour components must be in [0, 1]");
  return c;
}

// Keys of an object must be known: a typo should not be silently ignored.
void checkKeys(const Json& object, std::initializer_list<const char*> known, const Location& at) {
  if (!object.is_object()) at.fail("expected an object");
  for (const auto& item : object.items()) {
    bool found = false;
    std::string list;
    for (const char* k : known) {
      found = found || item.key() == k;
      list += (list.empty() ? "" : ", ") + std::string(k);
    }
    if (!found) at.fail("unknown key '" + item.key() + "' (known: " + list + ")");
  }
}

PrimitiveOptions readPrimitive(const Json& j, const Location& at) {
  checkKeys(j, {"kind", "resolution", "size"}, at);
  PrimitiveOptions options;
  const std::string kind = text(member(j, "kind", at), at / "kind");
  auto parsed = parsePrimitiveKind(kind);
  if (!parsed) at.fail("unknown primitive '" + kind + "' (known: sphere, cylinder, cube, cone, torus, plane)");
  options.kind = *parsed;
  if (j.contains("resolution")) {
    const Json& r = j["resolution"];
    if (!r.is_number_integer() || r.get<long long>() < 3 || r.get<long long>() > 4096)
      (at / "resolution").fail("expected an integer in [3, 4096], got " + r.dump());
    options.resolution = r.get<int>();
  }
  if (j.contains("size")) {
    options.size = number(j["size"], at / "size");
    if (options.size <= 0.0) (at / "size").fail("size must be positive");
  }
  return options;
}

SceneObject readObject(const Json& j, const Location& at) {
  checkKeys(j, {"name", "primitive", "display"}, at);
  SceneObject object;
  object.name = text(member(j, "name", at), at / "name");
  if (object.name.empty()) (at / "name").fail("object names must not be empty");
  object.primitive = readPrimitive(member(j, "primitive", at), at / "primitive");
  if (j.contains("display")) {
    const Json& d = j["display"];
    const Location dat = at / "display";
    checkKeys(d, {"color", "opacity", "visible"}, dat);
    if (d.contains("color")) object.display.color = colour(d["color"], dat / "color");
    if (d.contains("opacity")) {
      object.display.opacity = number(d["opacity"], dat / "opacity");
      if (object.display.opacity < 0.0 || object.display.opacity > 1.0) (dat / "opacity").fail("must be in [0, 1]");
    }
    if (d.contains("visible")) {
      if (!d["visible"].is_boolean()) (dat / "visible").fail("expected true or false");
      object.display.visible = d["visible"].get<bool>();
    }
  }
  try {
    object.mesh = makePrimitive(*object.primitive);
  } catch (const std::invalid_argument& e) {
    (at / "primitive").fail(e.what());
  }
  return object;
}

SceneLattice readLattice(const Json& j, const Location& at, const Scene& scene) {
  checkKeys(j, {"name", "objects", "counts", "padding"}, at);
  SceneLattice lattice;
  lattice.name = text(member(j, "name", at), at / "name");
  const Json& objects = member(j, "objects", at);
  if (!objects.is_array() || objects.empty()) (at / "objects").fail("expected a non-empty array of object names");
  for (std::size_t i = 0; i < objects.size(); ++i) {
    std::string name = text(objects[i], at / "objects" / i);
    if (scene.findObject(name) == nullptr) {
      std::string known;
      for (const auto& o : scene.objects) known += (known.empty() ? "" : ", ") + o.name;
      (at / "objects" / i).fail("unknown object '" + name + "' (known: " + known + ")");
    }
    lattice.objects.push_back(std::move(name));
  }
  const Json& counts = member(j, "counts", at);
  if (!counts.is_array() || counts.size() != 3) (at / "counts").fail("expected 3 integers");
  for (int a = 0; a < 3; ++a) {
    const Json& c = counts[static_cast<std::size_t>(a)];
    if (!c.is_number_integer() || c.get<long long>() < 2 || c.get<long long>() > 64)
      (at / "counts" / static_cast<std::size_t>(a)).fail("lattice needs 2..64 points per axis, got " + c.dump());
    lattice.counts[a] = c.get<int>();
  }
  if (j.contains("padding")) {
    lattice.padding = number(j["padding"], at / "padding");
    if (lattice.padding < 0.0) (at / "padding").fail("padding must be >= 0");
  }
  return lattice;
}

Scene readSceneJson(const Json& root, const std::string& source) {
  const Location at{source, ""};
  checkKeys(root, {"format", "version", "description", "background", "objects", "lattices", "camera"}, at);
  if (text(member(root, "format", at), at / "format") != "ffdkit-scene")
    (at / "format").fail("not an ffdkit scene (expected \"ffdkit-scene\")");
  const Json& version = member(root, "version", at);
  if (!version.is_number_integer()) (at / "version").fail("expected an integer");
  if (version.get<long long>() > kSceneFormatVersion || version.get<long long>() < 1) {
    (at / "version").fail("format version " + version.dump() + " is not supported by this build (reads 1.." +
                          std::to_string(kSceneFormatVersion) + ")");
  }
  Scene scene;
  if (root.contains("description")) scene.description = text(root["description"], at / "description");
  if (root.contains("background")) scene.background = colour(root["background"], at / "background");
  const Json& objects = member(root, "objects", at);
  if (!objects.is_array()) (at / "objects").fail("expected an array");
  for (std::size_t i = 0; i < objects.size(); ++i) {
    SceneObject object = readObject(objects[i], at / "objects" / i);
    if (scene.findObject(object.name) != nullptr)
      (at / "objects" / i / "name").fail("duplicate object name '" + object.name + "'");
    scene.objects.push_back(std::move(object));
  }
  if (root.contains("lattices")) {
    const Json& lattices = root["lattices"];
    if (!lattices.is_array()) (at / "lattices").fail("expected an array");
    for (std::size_t i = 0; i < lattices.size(); ++i)
      scene.lattices.push_back(readLattice(lattices[i], at / "lattices" / i, scene));
  }
  if (root.contains("camera")) {
    const Json& c = root["camera"];
    const Location cat = at / "camera";
    checkKeys(c, {"position", "focalPoint", "viewUp", "viewAngle"}, cat);
    scene.camera.position = vector3(member(c, "position", cat), cat / "position");
    scene.camera.focalPoint = vector3(member(c, "focalPoint", cat), cat / "focalPoint");
    scene.camera.viewUp = vector3(member(c, "viewUp", cat), cat / "viewUp");
    if (c.contains("viewAngle")) scene.camera.viewAngleDegrees = number(c["viewAngle"], cat / "viewAngle");
    if ((scene.camera.position - scene.camera.focalPoint).norm() == 0.0)
      cat.fail("camera position and focal point coincide");
    if (scene.camera.viewUp.norm() == 0.0) (cat / "viewUp").fail("view-up must be non-zero");
    if (scene.camera.viewAngleDegrees <= 0.0 || scene.camera.viewAngleDegrees >= 180.0)
      (cat / "viewAngle").fail("view angle must be in (0, 180) degrees");
  }
  return scene;
}

Json array3(const Eigen::Vector3d& v) { return Json::array({v.x(), v.y(), v.z()}); }

}  // namespace

Scene readScene(std::istream& in, const std::string& sourceName) {
  const std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Json root;
  try {
    root = Json::parse(content);
  } catch (const Json::parse_error& e) {
    // nlohmann's message starts with "[json.exception.parse_error.101] parse error at line ..."; keep its tail.
    std::string message = e.what();
    if (auto colon = message.find("syntax error"); colon != std::string::npos) message = message.substr(colon);
    throw SceneFileError(sourceName + ":" + lineColumn(content, e.byte == 0 ? 0 : e.byte - 1) + ": " + message);
  }
  return readSceneJson(root, sourceName);
}

Scene readScene(const std::filesystem::path& path) {
  const std::filesystem::path file = std::filesystem::is_directory(path) ? path / "scene.json" : path;
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SceneFileError(file.string() + ": cannot open scene file");
  return readScene(in, file.string());
}

void writeScene(std::ostream& out, const Scene& scene) {
  Json root;
  root["format"] = "ffdkit-scene";
  root["version"] = kSceneFormatVersion;
  if (!scene.description.empty()) root["description"] = scene.description;
  root["background"] = array3(scene.background);
  Json objects = Json::array();
  for (const auto& object : scene.objects) {
    Json o;
    o["name"] = object.name;
    if (object.primitive) {
      o["primitive"] = {{"kind", std::string(primitiveKindName(object.primitive->kind))},
                        {"resolution", object.primitive->resolution},
                        {"size", object.primitive->size}};
    }
    o["display"] = {{"color", array3(object.display.color)},
                    {"opacity", object.display.opacity},
                    {"visible", object.display.visible}};
    objects.push_back(std::move(o));
  }
  root["objects"] = std::move(objects);
  Json lattices = Json::array();
  for (const auto& lattice : scene.lattices) {
    lattices.push_back({{"name", lattice.name},
                        {"objects", lattice.objects},
                        {"counts", Json::array({lattice.counts.x(), lattice.counts.y(), lattice.counts.z()})},
                        {"padding", lattice.padding}});
  }
  root["lattices"] = std::move(lattices);
  root["camera"] = {{"position", array3(scene.camera.position)},
                    {"focalPoint", array3(scene.camera.focalPoint)},
                    {"viewUp", array3(scene.camera.viewUp)},
                    {"viewAngle", scene.camera.viewAngleDegrees}};
  out << root.dump(2) << '\n';
}

void writeScene(const std::filesystem::path& path, const Scene& scene) {
  std::ostringstream text;
  writeScene(text, scene);
  try {
    writeFileAtomically(path, text.str());
  } catch (const std::exception& e) {
    throw SceneFileError(e.what());
  }
}

}  // namespace ffdkit::scenes
