// ffdkit-cli render: a scene to PNG, off screen.
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "commands.h"
#include "console.h"
#include "ffdkit/app/offscreen_render.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/scene_file.h"

namespace ffdkit::cli {

namespace {

/// A camera looking at the bounding sphere of the deformed objects and the lattices along a preset direction, far
/// enough that the sphere fills the view angle with a small margin.
scenes::Camera presetCamera(const scenes::Scene& scene, const std::string& preset) {
  Eigen::Vector3d towardsCamera;
  Eigen::Vector3d up(0.0, 0.0, 1.0);
  if (preset == "front") {
    towardsCamera = {0.0, -1.0, 0.0};
  } else if (preset == "side") {
    towardsCamera = {1.0, 0.0, 0.0};
  } else if (preset == "top") {
    towardsCamera = {0.0, 0.0, 1.0};
    up = {0.0, 1.0, 0.0};
  } else if (preset == "iso") {
    towardsCamera = Eigen::Vector3d(1.0, -1.0, 1.0).normalized();
  } else {
    throw UsageError("--camera must be one of front, top, side, iso, scene; got '" + preset + "'");
  }
  Eigen::AlignedBox3d box;
  const auto deformed = scenes::deformScene(scene);
  for (const auto& object : scene.objects) {
    if (!object.display.visible) continue;
    const Eigen::MatrixX3d& points = deformed.at(object.name);
    for (Eigen::Index i = 0; i < points.rows(); ++i) box.extend(points.row(i).transpose());
  }
  // The lattices too: their handles are what the user grabs.
  for (auto lattice : scene.widgets.widgets(widgets::WidgetType::Lattice)) {
    const Eigen::MatrixX3d points = scene.widgets.worldControlPoints(lattice);
    for (Eigen::Index i = 0; i < points.rows(); ++i) box.extend(points.row(i).transpose());
  }
  if (box.isEmpty()) box.extend(Eigen::Vector3d::Zero());
  const double radius = std::max(0.5 * box.diagonal().norm(), 1e-6);
  scenes::Camera camera = scene.camera;
  const double halfAngle = 0.5 * camera.viewAngleDegrees * std::numbers::pi / 180.0;
  camera.focalPoint = box.center();
  camera.position = box.center() + towardsCamera * (1.1 * radius / std::sin(halfAngle));
  camera.viewUp = up;
  return camera;
}

int runRender(const Args& args) {
  Console console(args.flag("quiet"), args.flag("progress"), args.flag("timings"));
  if (args.positional().size() != 2) throw UsageError("render takes a SCENE and an OUTPUT.png");
  const std::filesystem::path scenePath = args.positional()[0];
  const std::filesystem::path png = args.positional()[1];
  app::OffscreenRenderOptions options;
  if (auto size = args.value("size")) parseSize(*size, "--size", options.width, options.height);
  const std::string preset = args.value("camera").value_or("scene");
  if (preset != "scene" && preset != "front" && preset != "top" && preset != "side" && preset != "iso")
    throw UsageError("--camera must be one of front, top, side, iso, scene; got '" + preset + "'");
  const auto settings = parseSettings(args.values("set"));

  console.begin("read", "reading " + scenePath.string());
  scenes::Scene scene = readSceneFile(scenePath, args);
  console.begin("build scene", "applying settings");
  applySettings(scene.widgets, settings);
  if (preset != "scene") scene.camera = presetCamera(scene, preset);
  console.begin("render", "rendering " + std::to_string(options.width) + "x" + std::to_string(options.height));
  app::renderSceneToPng(scene, png, options);
  console.end();
  console.say("wrote " + png.string());
  console.printTimings();
  return 0;
}

}  // namespace

Command renderCommand() {
  return {"render",
          "render a scene to PNG off screen",
          "ffdkit-cli render SCENE OUTPUT.png [--size WxH] [--camera PRESET] [--set NAME=VALUE]...",
          "Draws the scene's objects at their deformed points and its lattices, as the app shows\n"
          "them, into an off-screen window (needs an X display; use xvfb-run on a server).\n"
          "Camera presets: scene (the scene's own camera), front (from -y), side (from +x),\n"
          "top (from +z), iso (from (1,-1,1)); presets frame the deformed objects.\n",
          {{"size", '\0', "WxH", "image size in pixels (1024x768)"},
           {"camera", '\0', "PRESET", "scene, front, top, side or iso (scene)"},
           setOption(), allowOutsideMeshesOption(), quietOption(), progressOption(), timingsOption()},
          runRender};
}

}  // namespace ffdkit::cli
