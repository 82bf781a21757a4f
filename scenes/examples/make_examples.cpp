// Writes the sample scenes of scenes/examples/ from the scripting API, so that they stay in
// step with the code: `ffdkit-make-examples OUTDIR` writes OUTDIR/<name>/scene.json for every
// example. CTest runs it into a temporary folder and compares with the committed files
// (scripts/update-examples.sh rewrites them).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "ffdkit/ffd/cylindrical_lattice.h"
#include "ffdkit/scenes/scene_file.h"
#include "ffdkit/widgets/thesis_examples.h"

namespace {

using namespace ffdkit;
using scenes::Scene;
using widgets::AffineKind;
using widgets::CellSpec;

scenes::SceneObject primitiveObject(std::string name, scenes::PrimitiveOptions primitive, Eigen::Vector3d colour) {
  scenes::SceneObject object;
  object.name = std::move(name);
  object.source = primitive;
  object.display.color = colour;
  object.mesh = scenes::buildObjectMesh(object.source, ".");
  return object;
}

Eigen::Affine3d placedAt(const Eigen::Vector3d& centre) {
  return Eigen::Affine3d(Eigen::Translation3d(centre));
}

// A sphere with a 3x3x3 lattice fitted around it; a translate widget on the top face's centre
// point, pulled up a little so that the deformation shows.
Scene makeDefault() {
  Scene scene;
  scene.description = "A sphere with a 3x3x3 lattice attached; drag the arrow on top.";
  scene.objects.push_back(primitiveObject("sphere", {.kind = scenes::PrimitiveKind::Sphere, .resolution = 48},
                                          {0.85, 0.55, 0.30}));
  const auto lattice = scenes::attachNewLattice(scene, {"sphere"}, {.latticeName = "lattice"});
  const auto top = scene.widgets.addCell(lattice, CellSpec::point(1, 1, 2), "top");
  widgets::AffineOptions up;
  up.name = "pull";
  up.placement = Eigen::AngleAxisd(-std::numbers::pi / 2, Eigen::Vector3d::UnitY());  // local x -> world +z
  const auto pull = scene.widgets.addAffine(top, AffineKind::Translate, up);
  scene.widgets.setVariation(pull, 0.5);
  return scene;
}

Scene withThesisModel(std::string description, widgets::WidgetModel model, widgets::WidgetId root,
                      scenes::SceneObject object) {
  Scene scene;
  scene.description = std::move(description);
  scene.widgets = std::move(model);
  scene.objects.push_back(std::move(object));
  scene.attachments.push_back({scene.widgets.name(root), {scene.objects.front().name}});
  scene.camera.position = {2.9, -2.6, 2.3};
  scene.camera.focalPoint = {0.5, 0.5, 0.5};
  return scene;
}

// Fig. 6-10: a handle turned half a turn presses the top face down by half the pitch.
Scene makePress() {
  auto press = widgets::buildFig610(0.4, widgets::VariationRange{0.0, 0.3});
  press.model.setVariation(press.handle, std::numbers::pi);
  return withThesisModel("Fig. 6-10: a press. Turn the handle: one turn lowers the top face by the pitch (0.4).",
                         std::move(press.model), press.lattice,
                         primitiveObject("block", {.kind = scenes::PrimitiveKind::Cylinder, .resolution = 40, .size = 0.8,
                                                   .placement = placedAt({0.5, 0.5, 0.5})},
                                         {0.55, 0.7, 0.85}));
}

// A vise: two jaws (translate widgets on the faces x = 0 and x = 1, pointing inwards) bound
// mirror-wise, driven by a handle through a screw rule and stopped by a clamp range.
Scene makeVise() {
  widgets::WidgetModel model;
  const auto lattice = model.addLattice({.name = "vise", .counts = {3, 2, 2}});
  const auto left = model.addCell(lattice, CellSpec::slab(0, 0), "left-face");
  const auto right = model.addCell(lattice, CellSpec::slab(0, 2), "right-face");
  widgets::AffineOptions inwardsLeft;
  inwardsLeft.name = "left-jaw";
  inwardsLeft.placement = Eigen::AngleAxisd(-std::numbers::pi / 2, Eigen::Vector3d::UnitY());  // +x of the slab -> world +x
  const auto leftJaw = model.addAffine(left, AffineKind::Translate, inwardsLeft);
  widgets::AffineOptions inwardsRight = inwardsLeft;
  inwardsRight.name = "right-jaw";
  inwardsRight.placement = Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitY());
  const auto rightJaw = model.addAffine(right, AffineKind::Translate, inwardsRight);
  widgets::BindingOptions mirror;
  model.bind(leftJaw, rightJaw, mirror);
  widgets::AffineOptions handleOptions;
  handleOptions.name = "handle";
  handleOptions.placement = Eigen::Translation3d(-0.4, 0.5, 0.5) * Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitY());
  const auto handle = model.addFreeAffine(AffineKind::Rotate, handleOptions);
  widgets::BindingOptions screw;
  screw.rule = widgets::ConversionRule::screw(0.1);  // one turn closes each jaw by 0.1
  screw.rule.clamp = widgets::VariationRange{0.0, 0.3};
  model.bind(handle, leftJaw, screw);
  model.setVariation(handle, 2 * std::numbers::pi * 1.5);
  return withThesisModel("A vise: turn the handle; both jaws close symmetrically, 0.1 per turn, and stop at 0.3.",
                         std::move(model), lattice,
                         primitiveObject("part", {.kind = scenes::PrimitiveKind::Sphere, .resolution = 40, .size = 0.9,
                                                  .placement = placedAt({0.5, 0.5, 0.5})},
                                         {0.8, 0.75, 0.4}));
}

// Fig. 6-8: opposite translate widgets bound: a mirror-symmetric deformation.
Scene makeMirror() {
  auto fig = widgets::buildFig68();
  fig.model.setVariation(fig.faceTranslateA, 0.2);
  fig.model.setVariation(fig.edgeTranslateA, 0.15);
  return withThesisModel("Fig. 6-8: a 2x3x2 lattice; bound pairs of widgets move mirror-symmetrically about y = 0.5.",
                         std::move(fig.model), fig.lattice,
                         primitiveObject("torus", {.kind = scenes::PrimitiveKind::Torus, .resolution = 48, .size = 0.9,
                                                   .placement = placedAt({0.5, 0.5, 0.5}) *
                                                                Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX())},
                                         {0.45, 0.75, 0.5}));
}

// Fig. 6-9: a child lattice rides on the parent's top face.
Scene makeHierarchy() {
  auto fig = widgets::buildFig69();
  fig.model.setVariation(fig.faceLift, 0.2);
  fig.model.applyVariation(fig.childEdge, 0.15);
  Scene scene = withThesisModel("Fig. 6-9: a child lattice on the parent's top face follows it; the FFD runs parent then child.",
                         std::move(fig.model), fig.parent,
                         primitiveObject("column", {.kind = scenes::PrimitiveKind::Cylinder, .resolution = 40, .size = 0.7,
                                                    .placement = placedAt({0.5, 0.5, 0.5}) * Eigen::Scaling(1.0, 1.0, 1.35)},
                                         {0.7, 0.55, 0.85}));
  scene.camera.position = {3.4, -3.1, 3.0};
  scene.camera.focalPoint = {0.5, 0.5, 0.8};
  return scene;
}

// Fig. 6-11: a cylindrical lattice (EFFD) around a cylinder; its top ring is turned.
Scene makeCylinderTwist() {
  ffd::CylindricalLatticeOptions cylinder;
  cylinder.counts = {2, 12, 4};
  cylinder.bases = {ffd::AxisBasis::bspline(1), ffd::AxisBasis::periodic(3), ffd::AxisBasis::bspline(3)};
  cylinder.outerRadius = 0.7;  // the B-spline ring lies inside its control ring: keep the object inside
  cylinder.zMin = -0.55;
  cylinder.zMax = 0.55;
  const ffd::Lattice rest = ffd::makeCylindricalLattice(cylinder);
  widgets::WidgetModel model;
  widgets::LatticeOptions options;
  options.name = "cylinder-lattice";
  options.counts = cylinder.counts;
  options.restPoints = rest.restPoints();
  options.settings.basis = cylinder.bases;
  options.settings.cylinder = rest.cylinderRestShape();
  const auto lattice = model.addLattice(options);
  const auto top = model.addCell(lattice, CellSpec::slab(2, 3), "top-ring");
  widgets::AffineOptions twistOptions;
  twistOptions.name = "twist";
  const auto twist = model.addAffine(top, AffineKind::Rotate, twistOptions);
  model.setVariation(twist, std::numbers::pi / 2);
  Scene scene;
  scene.description = "Fig. 6-11: EFFD. A cylindrical lattice around a cylinder; its top ring turned 90 degrees.";
  scene.widgets = std::move(model);
  scene.objects.push_back(primitiveObject("cylinder", {.kind = scenes::PrimitiveKind::Cylinder, .resolution = 48},
                                          {0.9, 0.6, 0.45}));
  scene.attachments.push_back({"cylinder-lattice", {"cylinder"}});
  return scene;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: ffdkit-make-examples OUTDIR\n");
    return 2;
  }
  const std::filesystem::path out = argv[1];
  const std::vector<std::pair<const char*, std::function<Scene()>>> examples = {
      {"default", makeDefault}, {"press", makePress},         {"vise", makeVise},
      {"mirror", makeMirror},   {"hierarchy", makeHierarchy}, {"cylinder-twist", makeCylinderTwist},
  };
  try {
    for (const auto& [name, make] : examples) {
      std::filesystem::create_directories(out / name);
      ffdkit::scenes::writeScene(out / name / "scene.json", make());
      std::printf("wrote %s\n", (out / name / "scene.json").c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ffdkit-make-examples: %s\n", e.what());
    return 1;
  }
  return 0;
}
