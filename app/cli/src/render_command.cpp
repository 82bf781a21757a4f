// ffdkit-cli render: a scene to PNG, off screen. Built into the VTK module (modules.h); the
// command and its options are vtk_commands.cpp.
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "commands.h"
#include "module_functions.h"
#include "console.h"
#include "ffdkit/render/offscreen_render.h"
#include "ffdkit/scenes/animation.h"
#include "frames.h"
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
  for (const auto& object : scene.objects()) {
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
  scenes::Camera camera = scene.camera();
  const double halfAngle = 0.5 * camera.viewAngleDegrees * std::numbers::pi / 180.0;
  camera.focalPoint = box.center();
  camera.position = box.center() + towardsCamera * (1.1 * radius / std::sin(halfAngle));
  camera.viewUp = up;
  return camera;
}

}  // namespace

int runRender(const Args& args) {
  Console console(args.flag("quiet"), args.flag("progress"), args.flag("timings"));
  const auto output = args.value("output");
  if (args.positional().size() != (output ? 1u : 2u))
    throw UsageError("render takes a SCENE and an OUTPUT.png (or -o OUTPUT.png, or -o PATTERN with --frames)");
  const std::filesystem::path scenePath = args.positional()[0];
  const std::string target = output ? *output : args.positional()[1];
  app::OffscreenRenderOptions options;
  if (auto size = args.value("size")) parseSize(*size, "--size", options.width, options.height);
  const std::string preset = args.value("camera").value_or("scene");
  if (preset != "scene" && preset != "front" && preset != "top" && preset != "side" && preset != "iso")
    throw UsageError("--camera must be one of front, top, side, iso, scene; got '" + preset + "'");
  const auto settings = parseSettings(args.values("set"));
  const auto frameText = args.value("frame");
  const auto framesText = args.value("frames");
  if (frameText && framesText) throw UsageError("give --frame T or --frames A:B, not both");
  if (framesText) checkFramePattern(target);  // before reading anything
  const ReadSettings read = readSettings(args);

  console.begin("read", "reading " + scenePath.string());
  scenes::Scene scene = readSceneFile(scenePath, read);
  // Frames: the animation at each frame, then --set on top (a setting overrides a key).
  std::vector<std::pair<double, std::filesystem::path>> frames;
  if (framesText) {
    const FrameRange range = parseFrameRange(*framesText, scene.animation());
    for (int f = range.first; f <= range.last; ++f) frames.emplace_back(f, framePath(target, f));
  } else {
    frames.emplace_back(frameText ? parseFrame(*frameText, scene.animation()) : std::nan(""), target);
  }
  bool framed = false;
  for (const auto& [frame, png] : frames) {
    console.begin("build scene", "applying the animation and settings");
    if (!std::isnan(frame)) scenes::applyAnimationFrame(scene, frame);
    applySettings(scene.widgets, settings);
    if (preset != "scene" && !framed) {
      scene.setCamera(presetCamera(scene, preset));  // framed once: the camera holds still over a sequence
      framed = true;
    }
    console.begin("render", "rendering " + std::to_string(options.width) + "x" + std::to_string(options.height));
    app::renderSceneToPng(scene, png, options);
    console.end();
    console.say("wrote " + png.string());
  }
  console.printTimings();
  return 0;
}

}  // namespace ffdkit::cli
