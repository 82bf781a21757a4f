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
#include <tuple>
#include <vector>

#include "ffdkit/ffd/cylindrical_lattice.h"
#include "ffdkit/geometry/quaternion/curve_generators.h"
#include "ffdkit/scenes/animation.h"
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

// Keys an affine widget's variation at the given (frame, value) pairs (the scene's frame rate).
void keyVariation(Scene& scene, const char* widget, const std::vector<std::pair<int, double>>& keys,
                  scenes::Interpolation interpolation = scenes::Interpolation::Smooth) {
  const auto id = scene.widgets.find(widget);
  for (const auto& [frame, value] : keys) {
    scenes::Keyframe key;
    key.time = scenes::frameTime(scene.animation(), frame);
    key.variation = value;
    key.interpolation = interpolation;
    scenes::setKey(scene, id, scenes::ChannelKind::Variation, key);
  }
}

Eigen::Affine3d placedAt(const Eigen::Vector3d& centre) {
  return Eigen::Affine3d(Eigen::Translation3d(centre));
}

// A sphere with a 3x3x3 lattice fitted around it; a translate widget on the top face's centre
// point, pulled up a little so that the deformation shows.
// Changes the look of the scene's first object.
template <class Change>
void editLook(Scene& scene, Change change) {
  scenes::DisplaySettings look = scene.objects().front().display;
  change(look);
  scene.setObjectDisplay(scene.objects().front().name, look);
}

void aimCamera(Scene& scene, const Eigen::Vector3d& position, const Eigen::Vector3d& focalPoint) {
  scenes::Camera camera = scene.camera();
  camera.position = position;
  camera.focalPoint = focalPoint;
  scene.setCamera(camera);
}

Scene makeDefault() {
  Scene scene;
  scene.description = "A sphere with a 3x3x3 lattice attached; drag the arrow on top.";
  scene.addObject(primitiveObject("sphere", {.kind = scenes::PrimitiveKind::Sphere, .resolution = 48},
                                          {0.85, 0.55, 0.30}));
  scenes::AttachOptions attach;
  attach.latticeName = "lattice";
  const auto lattice = scenes::attachNewLattice(scene, {"sphere"}, attach);
  const auto top = scene.widgets.addCell(lattice, CellSpec::point(1, 1, 2), "top");
  widgets::AffineOptions up;
  up.name = "pull";
  up.placement = Eigen::AngleAxisd(-std::numbers::pi / 2, Eigen::Vector3d::UnitY());  // local x -> world +z
  scene.widgets.addAffine(top, AffineKind::Translate, up);
  aimCamera(scene, {3.0, -3.8, 2.7}, {0.0, 0.0, 0.3});  // far enough to see the arrow pulled to 0.5
  // Three seconds at 24 fps: the arrow rises to 0.5 at 1 s, dips, comes back. The file stores
  // frame 0 (the rest pose), so opening it and going to the first frame change nothing.
  keyVariation(scene, "pull", {{0, 0.0}, {24, 0.5}, {48, -0.2}, {72, 0.0}});
  return scene;
}

Scene withThesisModel(std::string description, widgets::WidgetModel model, widgets::WidgetId root,
                      scenes::SceneObject object) {
  Scene scene;
  scene.description = std::move(description);
  scene.widgets = std::move(model);
  scene.addObject(std::move(object));
  scene.attach(root, scene.objects().front().name);
  aimCamera(scene, {2.9, -2.6, 2.3}, {0.5, 0.5, 0.5});
  return scene;
}

// Fig. 6-10: a handle turned presses the top face down, one pitch per turn; at frame 36 (half a
// turn) by half the pitch. The file stores frame 0: the handle and the face at rest.
Scene makePress() {
  auto press = widgets::buildFig610(0.4, widgets::VariationRange{0.0, 0.3});
  Scene scene = withThesisModel("Fig. 6-10: a press. Turn the handle: one turn lowers the top face by the pitch (0.4).",
                                std::move(press.model), press.lattice,
                                primitiveObject("block", {.kind = scenes::PrimitiveKind::Cylinder, .resolution = 40, .size = 0.8,
                                                          .placement = placedAt({0.5, 0.5, 0.5})},
                                                {0.55, 0.7, 0.85}));
  aimCamera(scene, {3.2, -2.9, 2.9}, {0.5, 0.5, 0.8});  // the crank above the lattice in view too
  // One turn of the handle in three seconds, at a steady speed (the clamp stops the face at 0.3).
  keyVariation(scene, "handle", {{0, 0.0}, {72, 2 * std::numbers::pi}}, scenes::Interpolation::Linear);
  return scene;
}

// A vise: two jaws (translate widgets on the faces x = 0 and x = 1, pointing inwards) bound
// mirror-wise, driven by a handle through a screw rule and stopped by a clamp range.
Scene makeVise() {
  widgets::WidgetModel model;
  widgets::LatticeOptions latticeOptions;
  latticeOptions.name = "vise";
  latticeOptions.counts = {3, 2, 2};
  const auto lattice = model.addLattice(latticeOptions);
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
  Scene scene = withThesisModel("Fig. 6-8: a 2x3x2 lattice; bound pairs of widgets move mirror-symmetrically about y = 0.5.",
                                std::move(fig.model), fig.lattice,
                                primitiveObject("torus", {.kind = scenes::PrimitiveKind::Torus, .resolution = 48, .size = 0.9,
                                                          .placement = placedAt({0.5, 0.5, 0.5}) *
                                                                       Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX())},
                                                {0.45, 0.75, 0.5}));
  // One widget of each bound pair is keyed; its partner follows through the binding at every frame.
  // The file stores frame 0 (the rest pose); at frame 36 the face is pushed by 0.2 and the edge
  // pulled by 0.15.
  keyVariation(scene, "push-front", {{0, 0.0}, {36, 0.2}, {72, 0.0}});
  keyVariation(scene, "pull-front", {{0, 0.0}, {24, 0.15}}, scenes::Interpolation::Constant);
  return scene;
}

// Fig. 6-9: a child lattice rides on the parent's top face. It straddles the face, so the top of
// the column runs through both lattices: lifting the face stretches the column, and the child's
// widgets (child-push) bend its top. The child blends its change out below its box (a falloff
// of half its height) so that the column does not tear where it leaves the child.
Scene makeHierarchy() {
  auto fig = widgets::buildFig69();
  widgets::LatticeSettings childSettings = fig.model.latticeSettings(fig.child);
  childSettings.outside = ffd::OutsidePolicy::falloff(0.5);
  fig.model.setLatticeSettings(fig.child, childSettings);
  fig.model.setVariation(fig.faceLift, 0.2);
  fig.model.applyVariation(fig.childEdge, 0.15);
  Scene scene = withThesisModel("Fig. 6-9: a child lattice straddles the parent's top face and follows it; the FFD runs parent then child.",
                         std::move(fig.model), fig.parent,
                         primitiveObject("column", {.kind = scenes::PrimitiveKind::Cylinder, .resolution = 40, .size = 0.44,
                                                    .placement = placedAt({0.5, 0.5, 0.5}) * Eigen::Scaling(1.0, 1.0, 2.15)},
                                         {0.7, 0.55, 0.85}));
  aimCamera(scene, {3.4, -3.1, 3.0}, {0.5, 0.5, 0.8});
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
  // A rotate widget on every ring of control points above the bottom one; the top ring's
  // drives the others through variation bindings with gains 2/3 and 1/3, so that a turn of
  // the top twists the cylinder progressively instead of pinching it at one height.
  std::vector<widgets::WidgetId> turns;
  for (int k = 1; k <= 3; ++k) {
    const auto ring = model.addCell(lattice, CellSpec::slab(2, k), "ring-" + std::to_string(k));
    widgets::AffineOptions turn;
    turn.name = k == 3 ? "twist" : "turn-" + std::to_string(k);
    turns.push_back(model.addAffine(ring, AffineKind::Rotate, turn));
  }
  model.bind(turns[2], turns[1], widgets::ConversionRule(2.0 / 3.0));
  model.bind(turns[2], turns[0], widgets::ConversionRule(1.0 / 3.0));
  model.setVariation(turns[2], std::numbers::pi / 2);
  Scene scene;
  scene.description = "Fig. 6-11: EFFD. A cylindrical lattice twisting a cylinder: the top ring turned 90 degrees drives the rings below by 2/3 and 1/3.";
  scene.widgets = std::move(model);
  scene.addObject(primitiveObject("cylinder", {.kind = scenes::PrimitiveKind::Cylinder, .resolution = 48},
                                          {0.9, 0.6, 0.45}));
  scene.attach(scene.widgets.find("cylinder-lattice"), "cylinder");
  return scene;
}


// ---- Generated curves and surfaces (the geometry topics through the generator registry) ----

using scenes::GeneratorParameters;
using Rows = std::vector<std::vector<double>>;

Rows rowsOf(const Eigen::MatrixXd& matrix) {
  Rows rows;
  for (Eigen::Index r = 0; r < matrix.rows(); ++r) {
    std::vector<double> row;
    for (Eigen::Index c = 0; c < matrix.cols(); ++c) row.push_back(matrix(r, c));
    rows.push_back(std::move(row));
  }
  return rows;
}

// One generated object with a 3x3x3 lattice fitted around it; the top face's centre point is
// pulled up by a tenth of the object's size so that the deformation shows. The camera looks
// at the object from the front-right, above.
Scene generatedScene(std::string description, std::string objectName, std::string generator,
                     GeneratorParameters parameters, Eigen::Vector3d colour, double density = 1.0) {
  Scene scene;
  scene.description = std::move(description);
  scenes::SceneObject object;
  object.name = std::move(objectName);
  object.source = scenes::GeneratedSource{std::move(generator), std::move(parameters), density};
  object.display.color = colour;
  object.mesh = scenes::buildObjectMesh(object.source, ".");
  const Eigen::Vector3d low = object.mesh.points.colwise().minCoeff();
  const Eigen::Vector3d high = object.mesh.points.colwise().maxCoeff();
  const double size = (high - low).norm();
  scene.addObject(std::move(object));
  scenes::AttachOptions attach;
  attach.latticeName = "lattice";
  const auto lattice = scenes::attachNewLattice(scene, {scene.objects().front().name}, attach);
  const auto top = scene.widgets.addCell(lattice, CellSpec::point(1, 1, 2), "top");
  widgets::AffineOptions up;
  up.name = "pull";
  up.placement = Eigen::AngleAxisd(-std::numbers::pi / 2, Eigen::Vector3d::UnitY());  // local x -> world +z
  const auto pull = scene.widgets.addAffine(top, AffineKind::Translate, up);
  scene.widgets.setVariation(pull, std::round(100.0 * size) / 1000.0);
  const Eigen::Vector3d centre = 0.5 * (low + high);
  aimCamera(scene, centre + size * Eigen::Vector3d(0.9, -1.6, 1.1), centre);
  return scene;
}

// Miura 1998, Ex. 3 size: a G2 quaternion-integral curve through 7 points (docs/geometry-quaternion.md).
Scene makeQiInterpolate() {
  GeneratorParameters p;
  p.set("points", rowsOf(geometry::quaternion::exampleQiInterpolateParams().points));
  p.set("end-rule", std::string("circle3"));
  Scene scene = generatedScene(
      "Miura 1998: a G2 quaternion-integral curve through 7 points (Circle3 end tangents), in a lattice; its curvature "
      "comb follows the deformation.",
      "qi-curve", "qi-interpolate", std::move(p), {0.85, 0.35, 0.25});
  editLook(scene, [](scenes::DisplaySettings& look) { look.curvatureComb = true; });
  return scene;
}

// Sakiyama et al. 2001, Ex. 1: a noisy sine fitted by 4 quaternion-integral segments.
Scene makeQiFit() {
  const auto example = geometry::quaternion::exampleQiFitParams();
  GeneratorParameters p;
  p.set("points", rowsOf(example.points));
  p.set("breaks", std::vector<double>(example.breaks.begin(), example.breaks.end()));
  return generatedScene("Sakiyama et al. 2001, Ex. 1: 31 noisy points of a sine fitted by a G1 chain of 4 quaternion-integral segments.",
                        "fitted-sine", "qi-fit", std::move(p), {0.3, 0.55, 0.85});
}

// Sphere-tangent report, Fig. 15 analogue: one segment from (0,0,0) along x to (1,1,1) along z.
Scene makeSphereTangent() {
  GeneratorParameters p;
  p.set("start-point", std::vector<double>{0, 0, 0});
  p.set("start-tangent", std::vector<double>{1, 0, 0});
  p.set("end-point", std::vector<double>{1, 1, 1});
  p.set("end-tangent", std::vector<double>{0, 0, 1});
  p.set("degree", 2.0);
  return generatedScene("Sphere-tangent report: a tangent-integral curve from (0,0,0) along x to (1,1,1) along z (quadratic path on S^2).",
                        "space-curve", "sphere-tangent", std::move(p), {0.55, 0.35, 0.8});
}

// Kuroda et al. 1997, Fig. 2(c): the G3 curve with both end curvatures and the start angle given.
Scene makeG3Curve() {
  GeneratorParameters p;
  p.set("points", Rows{{0.6, 10.5}, {4, 11.2}, {7.2, 7.9}, {10.6, 5.7}, {13.9, 8.9}, {16.3, 14}, {19.8, 17.4}, {23.3, 16.6}});
  p.set("curvatures", Rows{{0, -0.10923218}, {-1, -0.16584946}});
  p.set("tangent-angles", Rows{{0, 0.546728}});
  return generatedScene("Kuroda et al. 1997, Fig. 2(c): a G3 curve (piecewise quadratic curvature) through 8 points, length 31.944.",
                        "g3-curve", "g3-curve", std::move(p), {0.2, 0.6, 0.45});
}

// Kuroda et al. 1997, Fig. 5: the G3 curve of 12 points with natural ends and its 4-clothoid
// approximation (clothoid-levels 2), one above the other, in one lattice.
Scene makeG3Clothoids() {
  const Rows points = {{6, 2}, {3.5, 7.5}, {8, 11}, {11.5, 8.5}, {9.5, 4.5}, {6, 9},
                       {6, 15}, {13, 17.5}, {20.5, 13}, {17.5, 7}, {14.5, 2}, {20, 1}};
  Scene scene;
  scene.description = "Kuroda et al. 1997, Fig. 5: a G3 curve (below) and its 4-clothoid-per-span approximation (above), one lattice.";
  for (const auto& [name, levels, z, colour] :
       {std::tuple{"g3-curve", 0.0, 0.0, Eigen::Vector3d(0.2, 0.6, 0.45)}, std::tuple{"clothoids", 2.0, 3.0, Eigen::Vector3d(0.85, 0.45, 0.2)}}) {
    GeneratorParameters p;
    p.set("points", points);
    p.set("clothoid-levels", levels);
    p.set("z", z);
    p.set("samples-per-span", 64.0);
    scenes::SceneObject object;
    object.name = name;
    object.source = scenes::GeneratedSource{"g3-curve", std::move(p), 1.0};
    object.display.color = colour;
    object.mesh = scenes::buildObjectMesh(object.source, ".");
    scene.addObject(std::move(object));
  }
  scenes::AttachOptions attach;
  attach.latticeName = "lattice";
  attach.counts = {4, 4, 2};
  const auto lattice = scenes::attachNewLattice(scene, {"g3-curve", "clothoids"}, attach);
  const auto corner = scene.widgets.addCell(lattice, CellSpec::point(3, 3, 1), "corner");
  widgets::AffineOptions out;
  out.name = "pull";
  const auto pull = scene.widgets.addAffine(corner, AffineKind::Translate, out);  // local x = world +x
  scene.widgets.setVariation(pull, 3.0);
  aimCamera(scene, {35.0, -31.0, 30.0}, {12.3, 9.3, 1.5});
  return scene;
}

// Kuriyama 1996, Fig. 3-7: the closed S-spline through the corners of a square, tension 5.
Scene makeSSplineCurve() {
  GeneratorParameters p;
  p.set("points", Rows{{1, 1, 0}, {-1, 1, 0}, {-1, -1, 0}, {1, -1, 0}});
  p.set("end", std::string("closed"));
  p.set("beta2", 5.0);
  p.set("samples-per-span", 32.0);
  return generatedScene("Kuriyama 1996, Fig. 3-7: a closed S-spline through the corners of a square, tension beta2 = 5.",
                        "s-spline", "s-spline-curve", std::move(p), {0.8, 0.5, 0.2});
}

// Kuriyama 1996, Fig. 3-15: a sigma-spline with cubic shape points through 6 points.
Scene makeSigmaSplineCurve() {
  GeneratorParameters p;
  p.set("points", Rows{{0, 0, 0}, {1, 1, 0}, {2, 0, 0}, {3, 1, 0}, {4, 0, 0}, {6, 2, 0}});
  p.set("shape", std::string("cubic"));
  p.set("samples-per-span", 32.0);
  return generatedScene("Kuriyama 1996, Fig. 3-15: a sigma-spline curve with cubic shape points through 6 points.",
                        "sigma-spline", "sigma-spline-curve", std::move(p), {0.25, 0.45, 0.8});
}

// A 9 x 9 wavy sheet interpolated by an S-spline surface.
Scene makeSSplineSurface() {
  Rows points;
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j) points.push_back({double(i), double(j), 0.6 * std::sin(0.8 * i) * std::cos(0.7 * j)});
  GeneratorParameters p;
  p.set("points", points);
  p.set("columns", 9.0);
  return generatedScene("Kuriyama 1996, ch. 3: an S-spline surface interpolating a 9 x 9 wavy grid.", "sheet", "s-spline-surface",
                        std::move(p), {0.5, 0.75, 0.55});
}

// Kuriyama 1996, ch. 3: a bicubic sigma-spline torus, closed in u and v.
Scene makeSigmaSplineSurface() {
  Rows points;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 6; ++j) {
      const double a = 2 * std::numbers::pi * i / 8, b = 2 * std::numbers::pi * j / 6;
      points.push_back({(2 + 0.5 * std::cos(b)) * std::cos(a), (2 + 0.5 * std::cos(b)) * std::sin(a), 0.5 * std::sin(b)});
    }
  GeneratorParameters p;
  p.set("points", points);
  p.set("columns", 6.0);
  p.set("closed-u", true);
  p.set("closed-v", true);
  Scene scene = generatedScene(
      "Kuriyama 1996, ch. 3: a bicubic sigma-spline torus interpolating an 8 x 6 closed grid, in zebra stripes (reflection "
      "lines) that show its smoothness under the deformation.",
      "torus", "sigma-spline-surface", std::move(p), {0.85, 0.65, 0.35});
  editLook(scene, [](scenes::DisplaySettings& look) { look.surfaceStyle = scenes::SurfaceStyle::Zebra; });
  return scene;
}

// Kuriyama 1996, Fig. 3-18/3-19: a circle and a star joined by a C2 blend: a vase.
Scene makeSplineBlend() {
  Rows circle, star;
  for (int i = 0; i < 4; ++i) {
    const double a = 2 * std::numbers::pi * i / 4;
    circle.push_back({std::cos(a), std::sin(a), 0});
    circle.push_back({1.2 * std::cos(a), 1.2 * std::sin(a), 1});
  }
  for (int i = 0; i < 10; ++i) {
    const double a = 2 * std::numbers::pi * i / 10, r = i % 2 == 0 ? 1.0 : 0.5;
    star.push_back({r * std::cos(a), r * std::sin(a), 3});
    star.push_back({1.2 * r * std::cos(a), 1.2 * r * std::sin(a), 4});
  }
  GeneratorParameters p;
  p.set("first-points", circle);
  p.set("first-columns", 2.0);
  p.set("first-closed-u", true);
  p.set("first-knots-u", std::vector<double>{0, 10, 20, 30, 40});
  p.set("first-knots-v", std::vector<double>{0, 10});
  p.set("second-points", star);
  p.set("second-columns", 2.0);
  p.set("second-closed-u", true);
  p.set("second-knots-u", std::vector<double>{0, 4, 8, 12, 16, 20, 24, 28, 32, 36, 40});
  p.set("second-knots-v", std::vector<double>{0, 10});
  p.set("part", std::string("composite"));
  return generatedScene("Kuriyama 1996, Fig. 3-19: a circle and a star (sigma-spline surfaces) joined by a C2 blend: a vase.",
                        "vase", "spline-blend", std::move(p), {0.45, 0.6, 0.85});
}

// Kuriyama 1996, Fig. 4-13: the hexagonal prism's G1 patch surface, its top ring's edges tightened.
Scene makePolyhedronSurface() {
  GeneratorParameters p;
  p.set("builtin-mesh", std::string("hexagonal-prism"));
  p.set("edge-beta", Rows{{6, 7, 10}, {7, 8, 10}, {8, 9, 10}, {9, 10, 10}, {10, 11, 10}, {11, 6, 10}});
  return generatedScene("Kuriyama 1996, Fig. 4-13: the G1 triangular-patch surface of a hexagonal prism, top edges at tension 10.",
                        "prism-surface", "polyhedron-surface", std::move(p), {0.75, 0.45, 0.6});
}

// Kuriyama 1996, Fig. 5-4: three great circles cut the sphere into octants; each octant is a
// three-sided patch of the curve-network surface.
Scene makeCurveNetworkSurface() {
  GeneratorParameters p;
  p.set("network", std::string("sphere-octants"));
  p.set("pitch", 8.0);
  return generatedScene("Kuriyama 1996, Fig. 5-4: a surface interpolating three great circles (eight three-sided patches).",
                        "octant-sphere", "curve-network-surface", std::move(p), {0.6, 0.7, 0.35});
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
      {"qi-interpolate", makeQiInterpolate},
      {"qi-fit", makeQiFit},
      {"sphere-tangent", makeSphereTangent},
      {"g3-curve", makeG3Curve},
      {"g3-clothoids", makeG3Clothoids},
      {"s-spline-curve", makeSSplineCurve},
      {"sigma-spline-curve", makeSigmaSplineCurve},
      {"s-spline-surface", makeSSplineSurface},
      {"sigma-spline-surface", makeSigmaSplineSurface},
      {"spline-blend", makeSplineBlend},
      {"polyhedron-surface", makePolyhedronSurface},
      {"curve-network-surface", makeCurveNetworkSurface},
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
