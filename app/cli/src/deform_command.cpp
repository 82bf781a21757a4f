// ffdkit-cli deform: applies a widget file or a scene's widget trees to meshes or point files.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <set>
#include <stdexcept>

#include "commands.h"
#include "console.h"
#include "ffdkit/scenes/mesh_io.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/scene_file.h"
#include "ffdkit/scenes/widget_file.h"
#include "input_mesh.h"

namespace ffdkit::cli {

namespace {

namespace fs = std::filesystem;

struct Output {
  std::string object;
  fs::path path;
};

std::string lower(std::string text) {
  for (char& ch : text) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return text;
}

/// The union of the world bounding boxes of the root lattices' rest shapes (with their subtrees'
/// frames following the roots, fitting the roots fits the whole tool).
Eigen::AlignedBox3d restBox(const widgets::WidgetModel& model) {
  Eigen::AlignedBox3d box;
  for (auto root : model.roots()) {
    const Eigen::MatrixX3d rest = model.worldRestPoints(root);
    for (Eigen::Index i = 0; i < rest.rows(); ++i) box.extend(rest.row(i).transpose());
  }
  return box;
}

/// --fit: one scale-and-translate map M takes the tool's rest box onto the objects' bounding
/// box grown by `padding` x its diagonal on every side (an axis flatter than 1e-3 of the
/// diagonal gets that thickness); every root frame F becomes M * F, so a tool of several
/// root lattices keeps its arrangement.
void fitRoots(scenes::Scene& scene, double padding) {
  Eigen::AlignedBox3d objects;
  for (const auto& object : scene.objects)
    for (Eigen::Index i = 0; i < object.mesh.points.rows(); ++i) objects.extend(object.mesh.points.row(i).transpose());
  const Eigen::AlignedBox3d tool = restBox(scene.widgets);
  if (objects.isEmpty() || tool.isEmpty()) throw std::runtime_error("--fit: nothing to fit (no points or no lattice)");
  const double diagonal = objects.diagonal().norm();
  if (!(diagonal > 0.0)) throw std::runtime_error("--fit: the inputs' bounding box is a single point");
  Eigen::Vector3d size = objects.sizes();
  for (int a = 0; a < 3; ++a) size[a] = std::max(size[a], 1e-3 * diagonal);
  size.array() += 2.0 * padding * diagonal;
  const Eigen::Vector3d toolSize = tool.sizes().cwiseMax(1e-12 * std::max(1.0, tool.diagonal().norm()));
  Eigen::Affine3d map = Eigen::Affine3d::Identity();
  map.translate(objects.center());
  map.scale(size.cwiseQuotient(toolSize));
  map.translate(-tool.center());
  for (auto root : scene.widgets.roots()) scene.widgets.setLatticeFrame(root, map * scene.widgets.latticeFrame(root));
}

std::string uniqueName(const std::string& stem, std::set<std::string>& taken) {
  const std::string wanted = stem.empty() ? "object" : stem;
  std::string name = wanted;
  for (int k = 2; taken.count(name) != 0; ++k) name = wanted + "-" + std::to_string(k);
  taken.insert(name);
  return name;
}

/// Writes every output or none: each mesh goes to a hidden temporary beside its target (same
/// folder, same extension so that the writer picks the format), and only when all are written
/// are they renamed onto their targets.
void writeAll(const std::vector<std::pair<fs::path, scenes::MeshData>>& outputs) {
  std::vector<std::pair<fs::path, fs::path>> staged;
  try {
    for (std::size_t i = 0; i < outputs.size(); ++i) {
      const fs::path& target = outputs[i].first;
      const fs::path temp = target.parent_path() / (".ffdkit-cli-" + std::to_string(::getpid()) + "-" +
                                                    std::to_string(i) + "-" + target.filename().string());
      staged.emplace_back(temp, target);
      scenes::writeMesh(temp, outputs[i].second);
    }
    for (const auto& [temp, target] : staged) fs::rename(temp, target);
  } catch (...) {
    std::error_code ignored;
    for (const auto& [temp, target] : staged) fs::remove(temp, ignored);
    throw;
  }
}

/// The command line of `deform`, checked.
struct DeformRequest {
  std::optional<fs::path> widgetFile;
  std::optional<fs::path> sceneFile;
  std::vector<std::string> inputs;
  fs::path output;
  bool fit = false;
  double padding = 0.05;
  std::vector<VariationSetting> settings;
  std::vector<std::string> objects;  ///< --object: the scene objects to write ("" = all)
  std::optional<std::string> format; ///< lower case, no dot
};

DeformRequest parseRequest(const Args& args) {
  DeformRequest r;
  if (auto w = args.value("widgets")) r.widgetFile = *w;
  if (auto s = args.value("scene")) r.sceneFile = *s;
  if (r.widgetFile.has_value() == r.sceneFile.has_value())
    throw UsageError("give exactly one of --widgets FILE and --scene FILE");
  const auto output = args.value("output");
  if (!output) throw UsageError("missing --output (-o) PATH");
  r.output = *output;
  r.inputs = args.positional();
  if (r.widgetFile && r.inputs.empty()) throw UsageError("--widgets needs at least one INPUT mesh or point file");
  r.fit = args.flag("fit");
  if (r.fit && r.inputs.empty()) throw UsageError("--fit fits the lattices to INPUT files; a scene's objects need none");
  if (auto padding = args.value("padding")) {
    if (!r.fit) throw UsageError("--padding only applies with --fit");
    r.padding = parseNumber(*padding, "--padding");
    if (r.padding < 0.0) throw UsageError("--padding must be >= 0");
  }
  r.settings = parseSettings(args.values("set"));
  r.objects = args.values("object");
  if (!r.objects.empty() && !r.inputs.empty())
    throw UsageError("--object selects objects of a scene without INPUT files");
  if (auto f = args.value("format")) {
    std::string format = lower(*f);
    if (!format.empty() && format[0] == '.') format.erase(0, 1);
    static const std::set<std::string> writable = {"obj", "ply", "stl", "vtp", "xyz"};
    if (writable.count(format) == 0) throw UsageError("--format must be one of obj, ply, stl, vtp, xyz; got '" + *f + "'");
    r.format = format;
  }
  return r;
}

/// Reads the tool or scene and the inputs, and builds the scene to evaluate: with INPUT files
/// every root lattice deforms every input. `sourceOf` receives each input object's file.
scenes::Scene loadScene(const DeformRequest& r, Console& console, std::map<std::string, fs::path>& sourceOf) {
  scenes::Scene scene;
  if (r.widgetFile) {
    console.begin("read", "reading " + r.widgetFile->string());
    scene.widgets = scenes::readWidgetFile(*r.widgetFile);
  } else {
    console.begin("read", "reading " + r.sceneFile->string());
    scene = scenes::readScene(*r.sceneFile);
  }
  if (!r.inputs.empty()) {
    std::vector<scenes::SceneObject> objects;
    std::set<std::string> taken;
    for (const auto& input : r.inputs) {
      console.begin("read", "reading " + input);
      scenes::SceneObject object;
      object.mesh = readInputMesh(fs::path(input));
      object.name = uniqueName(fs::path(input).stem().string(), taken);
      object.source = scenes::MeshFileSource{fs::absolute(input).string()};
      sourceOf[object.name] = input;
      objects.push_back(std::move(object));
    }
    scene.objects = std::move(objects);
  }

  console.begin("build scene", "building the scene");
  if (!r.inputs.empty()) {
    scene.attachments.clear();
    for (auto root : scene.widgets.roots()) {
      scenes::Attachment attachment{scene.widgets.name(root), {}};
      for (const auto& object : scene.objects) attachment.objects.push_back(object.name);
      scene.attachments.push_back(std::move(attachment));
    }
    if (scene.attachments.empty()) console.warn("the widget model has no lattice: the output equals the input");
  }
  if (r.fit) fitRoots(scene, r.padding);
  applySettings(scene.widgets, r.settings);
  scenes::validateScene(scene);
  return scene;
}

/// Where each object goes: -o is the file when there is one output, else (or when it is an
/// existing folder) the folder that receives NAME.EXT per object.
std::vector<Output> plannedOutputs(const DeformRequest& r, const scenes::Scene& scene,
                                   const std::map<std::string, fs::path>& sourceOf, bool& intoFolder) {
  std::vector<std::string> names;
  for (const auto& name : r.objects)
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  if (names.empty())
    for (const auto& object : scene.objects) names.push_back(object.name);
  for (const auto& name : names)
    if (!scene.findObject(name)) throw std::runtime_error("--object: the scene has no object '" + name + "'");
  if (names.empty()) throw std::runtime_error("nothing to deform: the scene has no objects");
  intoFolder = names.size() > 1 || fs::is_directory(r.output);
  std::vector<Output> targets;
  for (const auto& name : names) {
    if (!intoFolder) {
      if (r.output.extension().empty())
        throw UsageError("-o " + r.output.string() + ": no extension to pick a format by");
      targets.push_back({name, r.output});
      continue;
    }
    std::string ext = r.format.value_or("");
    if (ext.empty() && sourceOf.count(name)) ext = lower(sourceOf.at(name).extension().string());
    if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
    if (ext.empty() || ext == "gltf" || ext == "glb" || ext == "vtk")
      throw UsageError("give --format EXT for object '" + name + "' (its input format cannot be written)");
    targets.push_back({name, r.output / (name + "." + ext)});
  }
  return targets;
}

/// Evaluates in two timed steps with the same result as scenes::deformScene. "embed": one
/// update with every lattice at rest (the embeddings, plus an identity pass). "deform": the
/// edit from rest to the current control points, an exact incremental pass (child lattices,
/// whose input moved with their parent, re-embed here).
void evaluate(scenes::Scene& scene, scenes::SceneDeformer& deformer, Console& console) {
  Eigen::Index pointCount = 0;
  for (const auto& object : scene.objects) pointCount += object.mesh.points.rows();
  console.begin("embed", "embedding " + std::to_string(pointCount) + " points");
  const widgets::WidgetModelState current = scene.widgets.captureState();
  for (auto lattice : scene.widgets.widgets(widgets::WidgetType::Lattice))
    scene.widgets.setControlPoints(lattice, scene.widgets.restPoints(lattice));
  deformer.finishGesture(scene);
  scene.widgets.restoreState(current);
  console.begin("deform", "deforming " + std::to_string(pointCount) + " points");
  deformer.finishGesture(scene);
}

int runDeform(const Args& args) {
  Console console(args.flag("quiet"), args.flag("progress"), args.flag("timings"));
  const DeformRequest request = parseRequest(args);
  std::map<std::string, fs::path> sourceOf;
  scenes::Scene scene = loadScene(request, console, sourceOf);
  bool intoFolder = false;
  const std::vector<Output> targets = plannedOutputs(request, scene, sourceOf, intoFolder);
  scenes::SceneDeformer deformer;
  evaluate(scene, deformer, console);
  const scenes::SceneDeformStats stats = deformer.lastStats();

  std::vector<std::pair<fs::path, scenes::MeshData>> meshes;
  for (const auto& target : targets) {
    scenes::MeshData mesh = std::move(scene.findObject(target.object)->mesh);  // the scene is done with
    mesh.points = deformer.points(target.object);
    scenes::validateMesh(mesh, "deformed object '" + target.object + "'");
    meshes.emplace_back(target.path, std::move(mesh));
  }
  console.begin("write", "writing " + std::to_string(meshes.size()) + " file(s)");
  if (intoFolder) fs::create_directories(request.output);
  writeAll(meshes);
  console.end();

  for (const auto& [path, mesh] : meshes)
    console.say("wrote " + path.string() + " (" + std::to_string(mesh.points.rows()) + " points)");
  if (stats.failedPoints > 0)
    console.warn(std::to_string(stats.failedPoints) + " points failed to embed and were left unchanged");
  if (stats.outsidePoints > 0)
    console.say(std::to_string(stats.outsidePoints) + " points lie outside their lattice (outside policy applied)");
  console.printTimings();
  return 0;
}

}  // namespace

Command deformCommand() {
  return {"deform",
          "apply a widget file or a scene to meshes or point files and write the result",
          "ffdkit-cli deform --widgets TOOL.json INPUT... -o OUTPUT [options]\n"
          "       ffdkit-cli deform --scene SCENE [INPUT...] -o OUTPUT [options]",
          "With --widgets, every root lattice of the widget file deforms every INPUT where it lies\n"
          "(--fit first maps the lattices onto the inputs' bounding box). With --scene and INPUT\n"
          "files, the scene's root lattices deform the inputs the same way; without INPUT files\n"
          "the scene's own objects are deformed and written (--object picks some).\n"
          "INPUT: .obj .ply .stl .vtp .vtk .gltf .glb .xyz. OUTPUT: a file when there is one\n"
          "result (its extension picks the format: .obj .ply .stl .vtp .xyz), else a folder that\n"
          "receives NAME.EXT per object. Normals are recomputed when the input had them.\n"
          "Nothing is written when anything fails.\n",
          {{"widgets", 'w', "FILE", "the widget file (deformation tool) to apply"},
           {"scene", 's', "SCENE", "the scene (file or sample folder) whose widget trees to apply"},
           {"output", 'o', "PATH", "output file, or folder for several outputs"},
           setOption(),
           {"fit", '\0', "", "refit the root lattices' frames to the inputs' bounding box"},
           {"padding", '\0', "P", "with --fit: margin on every side, relative to the box diagonal (0.05)"},
           {"object", '\0', "NAME", "with --scene and no INPUT: write only this object", true},
           {"format", '\0', "EXT", "format of outputs written into a folder (default: the input's)"},
           quietOption(), progressOption(), timingsOption()},
          runDeform};
}

}  // namespace ffdkit::cli
