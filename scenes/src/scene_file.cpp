#include "ffdkit/scenes/scene_file.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <new>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "ffdkit/meshio/atomic_write.h"
#include "ffdkit/meshio/read_failures.h"
#include "ffdkit/scenes/animation.h"
#include "animation_checks.h"
#include "ffdkit/scenes/widget_file.h"
#include "json_text.h"
#include "widget_json.h"

namespace ffdkit::scenes {
namespace {

using detail::Json;

using Location = detail::JsonLocation<SceneFileError>;
using detail::checkKeys;
using detail::integerIn;
using detail::intIn;
using detail::member;
using detail::number;
using detail::text;
using detail::vector3;

Eigen::Vector3d colour(const Json& value, const Location& at) {
  const Eigen::Vector3d c = vector3(value, at);
  if ((c.array() < 0.0).any() || (c.array() > 1.0).any()) at.fail("colour components must be in [0, 1]");
  return c;
}

constexpr int kMaxPrimitiveResolution = 4096;
constexpr int kMaxZebraStripes = 256;

PrimitiveOptions readPrimitive(const Json& j, const Location& at) {
  checkKeys(j, {"kind", "resolution", "size", "placement"}, at);
  PrimitiveOptions options;
  const std::string kind = text(member(j, "kind", at), at / "kind");
  auto parsed = parsePrimitiveKind(kind);
  if (!parsed) (at / "kind").fail("unknown primitive '" + kind + "' (known: sphere, cylinder, cube, cone, torus, plane)");
  options.kind = *parsed;
  if (j.contains("resolution")) {
    options.resolution = intIn(j["resolution"], 3, kMaxPrimitiveResolution, at / "resolution");
  }
  if (j.contains("size")) {
    options.size = number(j["size"], at / "size");
    if (options.size <= 0.0) (at / "size").fail("size must be positive");
  }
  if (j.contains("placement")) {
    const Json& p = j["placement"];
    const Location pat = at / "placement";
    if (!p.is_array() || p.size() != 3) pat.fail("expected 3 rows of 4 numbers (a 3x4 affine matrix)");
    for (std::size_t r = 0; r < 3; ++r) {
      if (!p[r].is_array() || p[r].size() != 4) (pat / r).fail("expected 4 numbers");
      for (std::size_t c = 0; c < 4; ++c) options.placement.matrix()(Eigen::Index(r), Eigen::Index(c)) = number(p[r][c], pat / r / c);
    }
    if (std::abs(options.placement.linear().determinant()) < 1e-12) pat.fail("the placement is singular");
  }
  return options;
}

ParameterValue readParameter(const Json& v, const Location& at) {
  if (v.is_boolean()) return v.get<bool>();
  if (v.is_number()) return number(v, at);
  if (v.is_string()) return v.get<std::string>();
  if (v.is_array()) {
    if (v.empty() || v[0].is_number()) {
      std::vector<double> list;
      for (std::size_t i = 0; i < v.size(); ++i) list.push_back(number(v[i], at / i));
      return list;
    }
    std::vector<std::vector<double>> rows;
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!v[i].is_array()) (at / i).fail("expected a row of numbers like its siblings");
      std::vector<double> row;
      for (std::size_t k = 0; k < v[i].size(); ++k) row.push_back(number(v[i][k], at / i / k));
      rows.push_back(std::move(row));
    }
    return rows;
  }
  at.fail("expected a flag, a number, a string, a list of numbers or a list of rows");
}

Json writeParameter(const ParameterValue& value) {
  return std::visit([](const auto& v) { return Json(v); }, value);
}

SceneObject readObject(const Json& j, const Location& at, const SceneReadOptions& options,
                       const GeneratorRegistry& generators, meshio::ReadBudget& budget) {
  checkKeys(j, {"name", "primitive", "mesh", "generator", "display"}, at);
  SceneObject object;
  object.name = text(member(j, "name", at), at / "name");
  if (object.name.empty()) (at / "name").fail("object names must not be empty");
  const int sources = int(j.contains("primitive")) + int(j.contains("mesh")) + int(j.contains("generator"));
  if (sources != 1) at.fail("an object needs exactly one of 'primitive', 'mesh', 'generator'");
  if (j.contains("primitive")) {
    object.source = readPrimitive(j["primitive"], at / "primitive");
  } else if (j.contains("mesh")) {
    const Json& m = j["mesh"];
    checkKeys(m, {"path", "up"}, at / "mesh");
    MeshFileSource file{text(member(m, "path", at / "mesh"), at / "mesh" / "path")};
    if (m.contains("up")) {
      const std::string up = text(m["up"], at / "mesh" / "up");
      if (up == "y") file.up = UpAxis::Y;
      else if (up != "z") (at / "mesh" / "up").fail("unknown up axis '" + up + "' (known: z, y)");
    }
    object.source = file;
  } else {
    const Json& g = j["generator"];
    const Location gat = at / "generator";
    checkKeys(g, {"name", "parameters", "density"}, gat);
    GeneratedSource generated;
    generated.generator = text(member(g, "name", gat), gat / "name");
    if (!generators.contains(generated.generator)) {
      std::string list;
      for (const auto& n : generators.names()) list += (list.empty() ? "" : ", ") + n;
      (gat / "name").fail("unknown generator '" + generated.generator + "' (known: " + list + ")");
    }
    if (g.contains("parameters")) {
      const Json& params = g["parameters"];
      if (!params.is_object()) (gat / "parameters").fail("expected an object");
      for (const auto& item : params.items())
        generated.parameters.set(item.key(), readParameter(item.value(), gat / "parameters" / item.key()));
    }
    if (g.contains("density")) generated.density = number(g["density"], gat / "density");
    object.source = std::move(generated);
  }
  if (j.contains("display")) {
    const Json& d = j["display"];
    const Location dat = at / "display";
    checkKeys(d, {"color", "opacity", "visible", "surfaceStyle", "zebraStripes", "zebraDirection", "curvatureComb",
                  "combScale", "curveStyle"},
              dat);
    if (d.contains("color")) object.display.color = colour(d["color"], dat / "color");
    if (d.contains("opacity")) {
      object.display.opacity = number(d["opacity"], dat / "opacity");
      if (object.display.opacity < 0.0 || object.display.opacity > 1.0) (dat / "opacity").fail("must be in [0, 1]");
    }
    if (d.contains("visible")) {
      if (!d["visible"].is_boolean()) (dat / "visible").fail("expected true or false");
      object.display.visible = d["visible"].get<bool>();
    }
    if (d.contains("surfaceStyle")) {
      const std::string style = text(d["surfaceStyle"], dat / "surfaceStyle");
      if (style == "shaded") object.display.surfaceStyle = SurfaceStyle::Shaded;
      else if (style == "zebra") object.display.surfaceStyle = SurfaceStyle::Zebra;
      else (dat / "surfaceStyle").fail("unknown surface style '" + style + "' (known: shaded, zebra)");
    }
    if (d.contains("zebraStripes")) {
      object.display.zebraStripes = intIn(d["zebraStripes"], 1, kMaxZebraStripes, dat / "zebraStripes");
    }
    if (d.contains("zebraDirection")) {
      object.display.zebraDirection = vector3(d["zebraDirection"], dat / "zebraDirection");
      if (!(object.display.zebraDirection.norm() > 1e-12)) (dat / "zebraDirection").fail("must not be zero");
    }
    if (d.contains("curvatureComb")) {
      if (!d["curvatureComb"].is_boolean()) (dat / "curvatureComb").fail("expected true or false");
      object.display.curvatureComb = d["curvatureComb"].get<bool>();
    }
    if (d.contains("combScale")) {
      object.display.combScale = number(d["combScale"], dat / "combScale");
      if (!(object.display.combScale > 0.0)) (dat / "combScale").fail("must be positive");
    }
    if (d.contains("curveStyle")) {
      const std::string style = text(d["curveStyle"], dat / "curveStyle");
      if (style == "tube") object.display.curveStyle = CurveStyle::Tube;
      else if (style == "line") object.display.curveStyle = CurveStyle::Line;
      else (dat / "curveStyle").fail("unknown curve style '" + style + "' (known: tube, line)");
    }
  }
  try {
    object.mesh = buildObjectMesh(object.source, options.baseDirectory,
                                  ObjectMeshOptions{.generators = &generators, .budget = &budget, .confinement = options.confinement});
  } catch (const meshio::PathOutsideFolderError& e) {
    (at / "mesh" / "path").fail("object '" + object.name + "': " + e.what());
  } catch (const std::bad_alloc&) {
    throw;  // readScene's entry point names it with the budget
  } catch (const std::exception& e) {
    at.fail("object '" + object.name + "': " + e.what());
  }
  return object;
}

// A 3 x 4 affine matrix, as rows.
Eigen::Affine3d affineRows(const Json& p, const Location& at) {
  if (!p.is_array() || p.size() != 3) at.fail("expected 3 rows of 4 numbers (a 3x4 affine matrix)");
  Eigen::Affine3d m = Eigen::Affine3d::Identity();
  for (std::size_t r = 0; r < 3; ++r) {
    if (!p[r].is_array() || p[r].size() != 4) (at / r).fail("expected 4 numbers");
    for (std::size_t c = 0; c < 4; ++c) m.matrix()(Eigen::Index(r), Eigen::Index(c)) = number(p[r][c], at / r / c);
  }
  return m;
}

Json affineJson(const Eigen::Affine3d& m) {
  Json rows = Json::array();
  for (int r = 0; r < 3; ++r) {
    Json row = Json::array();
    for (int c = 0; c < 4; ++c) row.push_back(m.matrix()(r, c));
    rows.push_back(row);
  }
  return rows;
}

// "animation" (format version 2): frame rate, frame range, channels of keys naming their widget.
Animation readAnimation(const Json& j, const Location& at, const Scene& scene, meshio::ReadBudget& budget) {
  checkKeys(j, {"frameRate", "frames", "channels"}, at);
  Animation animation;
  if (j.contains("frameRate")) {
    animation.framesPerSecond = number(j["frameRate"], at / "frameRate");
    if (!(animation.framesPerSecond > 0.0 && animation.framesPerSecond <= kMaxFrameRate))
      (at / "frameRate").fail("expected frames per second in (0, 1000], got " + j["frameRate"].dump());
  }
  if (j.contains("frames")) {
    const Json& f = j["frames"];
    if (!f.is_array() || f.size() != 2) (at / "frames").fail("expected [first, last] frame numbers");
    const auto frame = [&](std::size_t k) {
      return static_cast<int>(integerIn(f[k], -std::int64_t(kMaxFrameMagnitude), std::int64_t(kMaxFrameMagnitude), at / "frames" / k));
    };
    animation.firstFrame = frame(0);
    animation.lastFrame = frame(1);
    if (animation.firstFrame > animation.lastFrame)
      (at / "frames").fail("the first frame " + f[0].dump() + " is after the last " + f[1].dump());
  }
  if (!j.contains("channels")) return animation;
  const Json& list = j["channels"];
  const Location lat = at / "channels";
  detail::checkArray(list, lat);
  if (list.size() > kMaxChannels)
    lat.fail("at most " + std::to_string(kMaxChannels) + " channels, got " + std::to_string(list.size()));
  std::size_t values = 0;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Json& c = list[i];
    const Location cat = lat / i;
    checkKeys(c, {"widget", "property", "keys"}, cat);
    const std::string widgetName = text(member(c, "widget", cat), cat / "widget");
    Channel channel;
    try {
      channel.widget = scene.widgets.find(widgetName);
    } catch (const widgets::WidgetError& e) {
      (cat / "widget").fail(e.what());
    }
    const std::string property = text(member(c, "property", cat), cat / "property");
    const auto kind = parseChannelKind(property);
    if (!kind) (cat / "property").fail("unknown property '" + property + "' (known: variation, frame, controlPoints)");
    channel.kind = *kind;
    if (findChannel(animation, channel.widget, channel.kind) != nullptr)
      cat.fail("a second '" + property + "' channel of widget '" + widgetName + "'");
    try {
      detail::checkKeyable(scene.widgets, channel.widget, channel.kind);
    } catch (const AnimationError& e) {
      (cat / "property").fail(e.what());
    }
    const Json& keys = member(c, "keys", cat);
    const Location kat = cat / "keys";
    detail::checkArray(keys, kat);
    if (keys.empty()) kat.fail("a channel needs at least one key");
    if (keys.size() > kMaxKeysPerChannel)
      kat.fail("at most " + std::to_string(kMaxKeysPerChannel) + " keys per channel, got " + std::to_string(keys.size()));
    const Eigen::Index pointCount =
        channel.kind == ChannelKind::ControlPoints ? scene.widgets.controlPoints(channel.widget).rows() : 0;
    // The keys are charged before they are built: each its own record, a control-point key its points.
    detail::chargeBytes(budget, keys.size(), sizeof(Keyframe), "the keys of channel " + std::to_string(i), kat);
    for (std::size_t k = 0; k < keys.size(); ++k) {
      const Json& kj = keys[k];
      const Location kloc = kat / k;
      checkKeys(kj, {"time", "value", "interpolation"}, kloc);
      Keyframe key;
      key.time = number(member(kj, "time", kloc), kloc / "time");
      if (kj.contains("interpolation")) {
        const std::string name = text(kj["interpolation"], kloc / "interpolation");
        const auto interpolation = parseInterpolation(name);
        if (!interpolation)
          (kloc / "interpolation").fail("unknown interpolation '" + name + "' (known: constant, linear, smooth)");
        key.interpolation = *interpolation;
      }
      const Json& value = member(kj, "value", kloc);
      switch (channel.kind) {
        case ChannelKind::Variation: key.variation = number(value, kloc / "value"); break;
        case ChannelKind::LatticeFrame: key.frame = affineRows(value, kloc / "value"); break;
        case ChannelKind::ControlPoints: {
          detail::checkArray(value, kloc / "value");
          if (Eigen::Index(value.size()) != pointCount)
            (kloc / "value").fail("expected " + std::to_string(pointCount) + " control points (lattice '" + widgetName +
                                "'), got " + std::to_string(value.size()));
          values += 3 * value.size();
          if (values > kMaxKeyValues) (kloc / "value").fail("the keys hold more than " + std::to_string(kMaxKeyValues) + " numbers");
          detail::chargeBytes(budget, std::uint64_t(pointCount), 3 * sizeof(double), "a key of " + std::to_string(pointCount) + " control points",
                              kloc / "value");
          key.points.resize(pointCount, 3);
          for (std::size_t p = 0; p < value.size(); ++p) key.points.row(Eigen::Index(p)) = vector3(value[p], kloc / "value" / p).transpose();
          break;
        }
      }
      if (const std::string problem = detail::keyProblem(scene.widgets, channel.widget, channel.kind, key); !problem.empty())
        kloc.fail(problem);
      if (k > 0 && !(key.time > channel.keys.back().time + 1e-9))
        (kloc / "time").fail("key times must increase: " + kj["time"].dump() + " after " + keys[k - 1]["time"].dump() +
                           " (keys are sorted and one per time)");
      channel.keys.push_back(std::move(key));
    }
    animation.channels.push_back(std::move(channel));
  }
  return animation;
}

// Whether a channel is written: a removed widget's keys go with it.
bool writtenChannel(const Scene& scene, const Channel& c) { return scene.widgets.contains(c.widget) && !c.keys.empty(); }

Json animationJson(const Scene& scene) {
  const Animation& animation = scene.animation();
  Json a;
  a["frameRate"] = animation.framesPerSecond;
  a["frames"] = Json::array({animation.firstFrame, animation.lastFrame});
  Json channels = Json::array();
  for (const Channel& c : animation.channels) {
    if (!writtenChannel(scene, c)) continue;
    Json keys = Json::array();
    for (const Keyframe& k : c.keys) {
      Json key;
      key["time"] = k.time;
      switch (c.kind) {
        case ChannelKind::Variation: key["value"] = k.variation; break;
        case ChannelKind::LatticeFrame: key["value"] = affineJson(k.frame); break;
        case ChannelKind::ControlPoints: {
          Json rows = Json::array();
          for (Eigen::Index p = 0; p < k.points.rows(); ++p) rows.push_back(Json::array({k.points(p, 0), k.points(p, 1), k.points(p, 2)}));
          key["value"] = std::move(rows);
          break;
        }
      }
      key["interpolation"] = std::string(interpolationName(k.interpolation));
      keys.push_back(std::move(key));
    }
    channels.push_back({{"widget", scene.widgets.name(c.widget)},
                        {"property", std::string(channelKindName(c.kind))},
                        {"keys", std::move(keys)}});
  }
  a["channels"] = std::move(channels);
  return a;
}

// Whether the animation writes nothing: the default rate and range, and no channel written (else
// a scene whose keyed widgets were removed would write "channels": [], which reads back as the
// default animation and so is not written again: not the same text).
bool isDefault(const Scene& scene) {
  const Animation& animation = scene.animation();
  const Animation defaults;
  return std::none_of(animation.channels.begin(), animation.channels.end(),
                      [&](const Channel& c) { return writtenChannel(scene, c); }) &&
         animation.framesPerSecond == defaults.framesPerSecond && animation.firstFrame == defaults.firstFrame &&
         animation.lastFrame == defaults.lastFrame;
}

Scene readSceneJson(const Json& root, const std::string& source, const SceneReadOptions& options, meshio::ReadBudget& budget) {
  const GeneratorRegistry& generators = options.generators != nullptr ? *options.generators : builtinGenerators();
  const Location at{&source, ""};
  checkKeys(root, {"format", "version", "description", "background", "objects", "widgets", "widgetFile",
                   "attachments", "camera", "animation"},
            at);
  if (text(member(root, "format", at), at / "format") != "ffdkit-scene")
    (at / "format").fail("not an ffdkit scene (expected \"ffdkit-scene\")");
  const Json& version = member(root, "version", at);
  const int fileVersion = intIn(version, 1, std::numeric_limits<int>::max(), at / "version");
  if (fileVersion > kSceneFormatVersion) {
    (at / "version").fail("format version " + version.dump() + " is not supported by this build (reads 1.." +
                          std::to_string(kSceneFormatVersion) + ")");
  }
  // Migration: version 1 (before animation) reads as version 2 without keys; nothing else changed.
  if (fileVersion < 2 && root.contains("animation"))
    (at / "animation").fail("'animation' needs format version 2 (this file says version " + version.dump() + ")");
  Scene scene;
  if (root.contains("description")) scene.description = text(root["description"], at / "description");
  if (root.contains("background")) scene.setBackground(colour(root["background"], at / "background"));
  const Json& objects = member(root, "objects", at);
  if (!objects.is_array()) (at / "objects").fail("expected an array");
  // The primitives are counted first, on a copy of the budget, so that a scene whose primitives
  // alone are over it fails before anything is built rather than after building those that fit
  // (a sphere at resolution 4096 takes most of a minute to weld). Objects with other errors are
  // left to the reading below, which reports them in file order.
  meshio::ReadBudget primitivesFirst = budget;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const Json& o = objects[i];
    if (!o.is_object() || !o.contains("primitive")) continue;
    PrimitiveOptions primitive;
    try {
      primitive = readPrimitive(o["primitive"], at / "objects" / i / "primitive");
    } catch (const SceneFileError&) {
      continue;
    }
    try {
      chargePrimitive(primitivesFirst, primitive);
    } catch (const meshio::ReadLimitError& e) {
      const std::string name = o.contains("name") && o["name"].is_string() ? o["name"].get<std::string>() : "";
      (at / "objects" / i).fail("object '" + name + "': " + e.what());
    }
  }
  for (std::size_t i = 0; i < objects.size(); ++i) {
    SceneObject object = readObject(objects[i], at / "objects" / i, options, generators, budget);
    if (scene.findObject(object.name) != nullptr)
      (at / "objects" / i / "name").fail("duplicate object name '" + object.name + "'");
    scene.addObject(std::move(object));
  }
  if (root.contains("widgets") && root.contains("widgetFile"))
    at.fail("give the widgets inline ('widgets') or by reference ('widgetFile'), not both");
  try {
    if (root.contains("widgets")) {
      scene.widgets = detail::widgetModelFromJson(root["widgets"], source, "/widgets", budget);
    } else if (root.contains("widgetFile")) {
      scene.widgetFile = text(root["widgetFile"], at / "widgetFile");
      std::filesystem::path file;
      try {
        file = meshio::confinedPath(options.baseDirectory, *scene.widgetFile, "widget file", options.confinement);
      } catch (const meshio::PathOutsideFolderError& e) {
        (at / "widgetFile").fail(e.what());
      }
      scene.widgets = readWidgetFile(file, WidgetReadOptions{.limits = budget.limits(), .budget = &budget});
    }
  } catch (const WidgetFileError& e) {
    throw SceneFileError(std::string(e.what()) + (root.contains("widgetFile") ? " (widget file of " + source + ")" : ""));
  }
  if (root.contains("attachments")) {
    const Json& list = root["attachments"];
    if (!list.is_array()) (at / "attachments").fail("expected an array");
    std::vector<Attachment> attachments;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Location aat = at / "attachments" / i;
      checkKeys(list[i], {"lattice", "objects"}, aat);
      Attachment attachment;
      // The file names the lattice (readable); the scene holds its id, which a rename keeps.
      const std::string lattice = text(member(list[i], "lattice", aat), aat / "lattice");
      try {
        attachment.lattice = scene.widgets.find(lattice);
      } catch (const std::exception& e) {
        (aat / "lattice").fail(std::string("attachment of '") + lattice + "': " + e.what());
      }
      const Json& names = member(list[i], "objects", aat);
      if (!names.is_array() || names.empty()) (aat / "objects").fail("expected a non-empty array of object names");
      // The file names the objects; the scene holds their ids.
      for (std::size_t k = 0; k < names.size(); ++k) {
        const std::string name = text(names[k], aat / "objects" / k);
        const SceneObject* object = scene.findObject(name);
        if (object == nullptr)
          (aat / "objects" / k).fail("lattice '" + lattice + "' is attached to unknown object '" + name + "'");
        attachment.objects.push_back(object->id);
      }
      attachments.push_back(std::move(attachment));
    }
    scene.setAttachments(std::move(attachments));
  }
  if (root.contains("camera")) {
    const Json& c = root["camera"];
    const Location cat = at / "camera";
    checkKeys(c, {"position", "focalPoint", "viewUp", "viewAngle"}, cat);
    Camera camera;
    camera.position = vector3(member(c, "position", cat), cat / "position");
    camera.focalPoint = vector3(member(c, "focalPoint", cat), cat / "focalPoint");
    camera.viewUp = vector3(member(c, "viewUp", cat), cat / "viewUp");
    if (c.contains("viewAngle")) camera.viewAngleDegrees = number(c["viewAngle"], cat / "viewAngle");
    if ((camera.position - camera.focalPoint).norm() == 0.0) cat.fail("camera position and focal point coincide");
    if (camera.viewUp.cross(camera.focalPoint - camera.position).norm() == 0.0)
      (cat / "viewUp").fail("view-up must be non-zero and not along the view direction");
    if (camera.viewAngleDegrees <= 0.0 || camera.viewAngleDegrees >= 180.0)
      (cat / "viewAngle").fail("view angle must be in (0, 180) degrees");
    scene.setCamera(camera);
  }
  try {
    validateScene(scene);
  } catch (const std::invalid_argument& e) {
    (at / "attachments").fail(e.what());
  }
  if (root.contains("animation")) {
    scene.setAnimation(readAnimation(root["animation"], at / "animation", scene, budget));
    try {
      validateAnimation(scene);
    } catch (const AnimationError& e) {
      (at / "animation").fail(e.what());
    }
  }
  return scene;
}

Json array3(const Eigen::Vector3d& v) { return Json::array({v.x(), v.y(), v.z()}); }

Json sceneJson(const Scene& scene) {
  Json root;
  root["format"] = "ffdkit-scene";
  root["version"] = kSceneFormatVersion;
  if (!scene.description.empty()) root["description"] = scene.description;
  root["background"] = array3(scene.background());
  Json objects = Json::array();
  for (const auto& object : scene.objects()) {
    Json o;
    o["name"] = object.name;
    if (const auto* primitive = std::get_if<PrimitiveOptions>(&object.source)) {
      Json p = {{"kind", std::string(primitiveKindName(primitive->kind))},
                {"resolution", primitive->resolution},
                {"size", primitive->size}};
      if (!primitive->placement.isApprox(Eigen::Affine3d::Identity(), 0.0)) {
        Json rows = Json::array();
        for (int r = 0; r < 3; ++r) {
          Json row = Json::array();
          for (int c = 0; c < 4; ++c) row.push_back(primitive->placement.matrix()(r, c));
          rows.push_back(row);
        }
        p["placement"] = rows;
      }
      o["primitive"] = p;
    } else if (const auto* file = std::get_if<MeshFileSource>(&object.source)) {
      o["mesh"] = {{"path", file->path}};
      if (file->up != UpAxis::Z) o["mesh"]["up"] = std::string(upAxisName(file->up));  // older files keep their bytes
    } else {
      const auto& generated = std::get<GeneratedSource>(object.source);
      Json parameters = Json::object();
      for (const auto& [name, value] : generated.parameters.values()) parameters[name] = writeParameter(value);
      o["generator"] = {{"name", generated.generator}, {"parameters", parameters}, {"density", generated.density}};
    }
    o["display"] = {{"color", array3(object.display.color)},
                    {"opacity", object.display.opacity},
                    {"visible", object.display.visible}};
    // The look keys added later are written only when set, so older scene files keep their bytes.
    const DisplaySettings defaults;
    Json& display = o["display"];
    if (object.display.surfaceStyle != defaults.surfaceStyle)
      display["surfaceStyle"] = object.display.surfaceStyle == SurfaceStyle::Zebra ? "zebra" : "shaded";
    if (object.display.zebraStripes != defaults.zebraStripes) display["zebraStripes"] = object.display.zebraStripes;
    if (object.display.zebraDirection != defaults.zebraDirection)
      display["zebraDirection"] = array3(object.display.zebraDirection);
    if (object.display.curvatureComb != defaults.curvatureComb) display["curvatureComb"] = object.display.curvatureComb;
    if (object.display.combScale != defaults.combScale) display["combScale"] = object.display.combScale;
    if (object.display.curveStyle != defaults.curveStyle)
      display["curveStyle"] = object.display.curveStyle == CurveStyle::Line ? "line" : "tube";
    objects.push_back(std::move(o));
  }
  root["objects"] = std::move(objects);
  if (scene.widgetFile) {
    root["widgetFile"] = *scene.widgetFile;
  } else {
    root["widgets"] = detail::widgetModelToJson(scene.widgets);
  }
  Json attachments = Json::array();
  for (const auto& a : scene.attachments()) {
    if (!scene.widgets.contains(a.lattice))
      throw std::invalid_argument("scene: an attachment holds lattice " + widgets::toString(a.lattice) +
                                  ", which the widget model does not have");
    Json objectNames = Json::array();
    for (const ObjectId object : a.objects) objectNames.push_back(scene.objectName(object));
    attachments.push_back({{"lattice", scene.widgets.name(a.lattice)}, {"objects", std::move(objectNames)}});
  }
  root["attachments"] = std::move(attachments);
  root["camera"] = {{"position", array3(scene.camera().position)},
                    {"focalPoint", array3(scene.camera().focalPoint)},
                    {"viewUp", array3(scene.camera().viewUp)},
                    {"viewAngle", scene.camera().viewAngleDegrees}};
  // Written only when there is something to say: a scene without keys stays as short as before.
  if (!isDefault(scene)) root["animation"] = animationJson(scene);
  return root;
}

}  // namespace

namespace {

// The rest of `in`, a block at a time (a string built from istreambuf_iterator grows a character
// at a time: 3 % of a release build's time over the scene fuzz target's corpus).
std::string streamText(std::istream& in) {
  std::string content;
  char block[16384];
  while (in.read(block, sizeof block) || in.gcount() > 0) content.append(block, static_cast<std::size_t>(in.gcount()));
  return content;
}

// Reads the text of a scene from `in` after charging `knownSize` bytes (the file's size, when
// known) or, for a stream of unknown size, what it held; then the whole scene against the same
// budget. The one place that turns a failed allocation, or a budget overrun that escaped a located
// check, into a SceneFileError.
Scene readSceneStream(std::istream& in, std::optional<std::uint64_t> knownSize, const std::string& sourceName,
                      const SceneReadOptions& options) {
  meshio::ReadBudget budget(options.limits);
  return meshio::convertReadFailures<SceneFileError>(sourceName, "the scene", budget, [&] {
    if (knownSize) budget.chargeBytes(*knownSize, 1, "the text of the scene file");
    const std::string content = streamText(in);
    if (!knownSize) budget.chargeBytes(content.size(), 1, "the text of the scene file");
    return readSceneJson(detail::parseJson<SceneFileError>(content, sourceName, budget), sourceName, options, budget);
  });
}

}  // namespace

Scene readScene(std::istream& in, const std::string& sourceName, const SceneReadOptions& options) {
  return readSceneStream(in, std::nullopt, sourceName, options);
}

Scene readScene(const std::filesystem::path& path, SceneReadOptions options) {
  const std::filesystem::path file = std::filesystem::is_directory(path) ? path / "scene.json" : path;
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SceneFileError(file.string() + ": cannot open scene file");
  options.baseDirectory = file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  return readSceneStream(in, ec ? std::nullopt : std::optional<std::uint64_t>(size), file.string(), options);
}

Scene readScene(const std::filesystem::path& path) { return readScene(path, SceneReadOptions{}); }

GeneratorParameters readGeneratorParameters(std::istream& in, const std::string& sourceName) {
  const std::string content = streamText(in);
  const Json root = detail::parseJson<SceneFileError>(content, sourceName);
  const Location at{&sourceName, ""};
  detail::checkObject(root, at);
  GeneratorParameters parameters;
  for (const auto& item : root.items()) parameters.set(item.key(), readParameter(item.value(), at / item.key()));
  return parameters;
}

GeneratorParameters readGeneratorParameters(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneFileError(path.string() + ": cannot open the parameter file");
  return readGeneratorParameters(in, path.string());
}

std::string sceneFileText(const Scene& scene) { return detail::canonicalJsonText(sceneJson(scene)); }

void writeScene(std::ostream& out, const Scene& scene) { out << sceneFileText(scene); }

void writeScene(const std::filesystem::path& path, const Scene& scene, const SceneWriteOptions& options) {
  const std::string text = sceneFileText(scene);  // before touching any file: nothing half-written
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  // The reader's confinement rule, before anything is written: a path it would refuse is refused
  // here, so a written scene always reads back (under the same rule) and no widget file lands
  // outside the folder.
  const auto confined = [&](const std::string& named, std::string_view what, const std::string& pointer,
                            const std::string& object) {
    try {
      return meshio::confinedPath(folder, named, what, options.confinement);
    } catch (const meshio::PathOutsideFolderError& e) {
      throw SceneFileError(path.string() + " " + pointer + ": " + (object.empty() ? "" : "object '" + object + "': ") + e.what() +
                           "; nothing written: the scene would not read back");
    }
  };
  for (std::size_t i = 0; i < scene.objects().size(); ++i) {
    const SceneObject& object = scene.objects()[i];
    if (const auto* file = std::get_if<MeshFileSource>(&object.source))
      confined(file->path, "mesh file", "/objects/" + std::to_string(i) + "/mesh/path", object.name);
  }
  std::optional<std::filesystem::path> widgetPath;
  if (scene.widgetFile) widgetPath = confined(*scene.widgetFile, "widget file", "/widgetFile", "");
  try {
    if (widgetPath) writeWidgetFile(*widgetPath, scene.widgets);
    meshio::writeFileAtomically(path, text);
  } catch (const std::exception& e) {
    throw SceneFileError(e.what());
  }
}

void writeScene(const std::filesystem::path& path, const Scene& scene) { writeScene(path, scene, SceneWriteOptions{}); }

}  // namespace ffdkit::scenes
