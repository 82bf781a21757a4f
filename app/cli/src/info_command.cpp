// ffdkit-cli info and validate: summarise and check scene, widget and mesh files.
#include <cmath>
#include <cstdio>
#include <sstream>

#include "commands.h"
#include "console.h"
#include "decomposed_case.h"
#include "shape_guard.h"
#include "volume_mesh.h"
#include "ffdkit/scenes/mesh_io.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/scene_file.h"
#include "ffdkit/scenes/widget_file.h"

namespace ffdkit::cli {

namespace {

namespace fs = std::filesystem;

std::string boxText(const Eigen::MatrixX3d& points) {
  if (points.rows() == 0) return "empty";
  const Eigen::Vector3d lo = points.colwise().minCoeff();
  const Eigen::Vector3d hi = points.colwise().maxCoeff();
  return format("[%g, %g, %g] .. [%g, %g, %g]", lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z());
}

std::string meshText(const scenes::MeshData& mesh) {
  return format("%lld points, %lld triangles, %lld segments%s, bounds %s", static_cast<long long>(mesh.points.rows()),
                static_cast<long long>(mesh.triangles.rows()), static_cast<long long>(mesh.segments.rows()),
                mesh.hasNormals ? ", normals" : "", boxText(mesh.points).c_str());
}

std::string sourceText(const scenes::ObjectSource& source) {
  if (const auto* p = std::get_if<scenes::PrimitiveOptions>(&source))
    return format("primitive %s (resolution %d)", std::string(scenes::primitiveKindName(p->kind)).c_str(), p->resolution);
  if (const auto* m = std::get_if<scenes::MeshFileSource>(&source)) return "mesh file " + m->path;
  const auto& g = std::get<scenes::GeneratedSource>(source);
  return format("generator %s (density %g)", g.generator.c_str(), g.density);
}

void printWidgets(const widgets::WidgetModel& model) {
  for (auto lattice : model.pipelineOrder()) {
    const Eigen::Vector3i n = model.counts(lattice);
    const auto parent = model.parentLattice(lattice);
    // A rational lattice (Lamousin & Waggenspack 1994) says so, with the range of its weights.
    std::string rational;
    if (model.isRational(lattice)) {
      const Eigen::VectorXd w = model.weights(lattice);
      rational = format(", rational (weights %g to %g)", w.minCoeff(), w.maxCoeff());
    }
    std::printf("lattice %s: %dx%dx%d control points, %s, %zu cells%s\n", model.name(lattice).c_str(), n.x(), n.y(),
                n.z(), parent ? ("child of " + model.name(*parent)).c_str() : "root", model.cellsOf(lattice).size(),
                rational.c_str());
  }
  for (auto affine : model.widgets(widgets::WidgetType::Affine)) {
    const auto cell = model.attachedCell(affine);
    std::printf("affine %s: %s, variation %g, %s\n", model.name(affine).c_str(),
                std::string(widgets::affineKindName(model.affineKind(affine))).c_str(), model.variation(affine),
                cell ? ("on cell " + model.name(*cell)).c_str() : "free");
  }
  std::printf("bindings: %zu\n", model.bindings().size());
  const std::vector<std::string> folds = foldFindings(model);
  if (folds.empty() && !model.pipelineOrder().empty()) std::printf("fold-over: every lattice certified free of it\n");
  for (const auto& line : folds) std::printf("fold-over: %s\n", line.c_str());
}

/// validate's note on fold-over: "" when every lattice is certified free of it.
std::string foldNote(const widgets::WidgetModel& model) {
  std::string note;
  for (const auto& line : foldFindings(model)) note += "; fold-over: " + line;
  return note;
}

void infoScene(const fs::path& path, const ReadSettings& read) {
  const scenes::Scene scene = readSceneFile(path, read);
  std::printf("scene: %s\n", path.string().c_str());
  if (!scene.description.empty()) std::printf("description: %s\n", scene.description.c_str());
  if (scene.widgetFile) std::printf("widget file: %s\n", scene.widgetFile->c_str());
  for (const auto& object : scene.objects())
    std::printf("object %s: %s; %s\n", object.name.c_str(), sourceText(object.source).c_str(),
                meshText(object.mesh).c_str());
  printWidgets(scene.widgets);
  for (const auto& a : scene.attachments()) {
    std::string objects;
    for (const auto o : a.objects) objects += (objects.empty() ? "" : ", ") + scene.objectName(o);
    std::printf("attachment: %s deforms %s\n", scene.widgets.name(a.lattice).c_str(), objects.c_str());
  }
  scenes::SceneDeformer deformer;
  deformer.evaluate(scene);  // syncs and runs the exact pipeline in one pass
  const auto& stats = deformer.lastStats();
  std::printf("evaluated: %lld points deformed (%lld outside their lattice, %lld failed to embed)\n",
              static_cast<long long>(stats.deformedPoints), static_cast<long long>(stats.outsidePoints),
              static_cast<long long>(stats.failedPoints));
}

void infoWidgets(const fs::path& path, const ReadSettings& read) {
  const widgets::WidgetModel model = readWidgetsFile(path, read);
  std::printf("widget file: %s\n", path.string().c_str());
  printWidgets(model);
}

void infoMesh(const fs::path& path, const ReadSettings& read) {
  const scenes::MeshData mesh = readMeshFile(path, read);
  std::printf("mesh: %s\n%s\n", path.string().c_str(), meshText(mesh).c_str());
}

int runInfo(const Args& args) {
  if (args.flag("generators")) {
    if (!args.positional().empty()) throw UsageError("--generators takes no FILE");
    const auto& registry = scenes::builtinGenerators();
    const auto names = registry.names();
    if (names.empty()) std::printf("no generators registered\n");
    for (const auto& name : names) {
      const auto& g = registry.get(name);
      std::string params;
      for (const auto& p : g.parameterNames) params += (params.empty() ? "" : ", ") + p;
      std::printf("%s (%s): %s; parameters: %s\n", name.c_str(), g.profile ? "curve" : "surface", g.summary.c_str(),
                  params.c_str());
    }
    return 0;
  }
  if (args.positional().empty()) throw UsageError("info takes one or more FILEs (or --generators)");
  const ReadSettings read = readSettings(args);
  const std::optional<fs::path> tool = args.value("widgets");
  bool first = true;
  for (const auto& file : args.positional()) {
    if (!first) std::printf("\n");
    first = false;
    if (meshio::isDecomposedOpenFoamCase(file)) {
      if (tool) throw UsageError("--widgets TOOL checks one mesh; for a decomposed case run deform on it");
      infoDecomposedCase(file, read, args.flag("quality"));
      continue;
    }
    if (isVolumeMesh(file)) {
      infoVolumeMesh(file, read, args.flag("quality"), tool ? &*tool : nullptr);
      continue;
    }
    switch (fileKind(file)) {
      case FileKind::Scene: infoScene(file, read); break;
      case FileKind::Widgets: infoWidgets(file, read); break;
      case FileKind::Mesh: infoMesh(file, read); break;
    }
  }
  return 0;
}

/// Checks one file completely: reads it, builds every object, validates references and meshes,
/// and evaluates a scene (a degenerate lattice fails there). @throws on the first problem.
std::string check(const fs::path& path, const ReadSettings& read) {
  if (meshio::isDecomposedOpenFoamCase(path)) return checkDecomposedCase(path, read);
  if (isVolumeMesh(path)) return checkVolumeMesh(path, read);
  switch (fileKind(path)) {
    case FileKind::Scene: {
      const scenes::Scene scene = readSceneFile(path, read);
      scenes::validateScene(scene);
      for (const auto& object : scene.objects())
        scenes::validateMesh(object.mesh, path.string() + ": object '" + object.name + "'");
      const auto deformed = scenes::deformScene(scene);
      for (const auto& [name, points] : deformed) {
        if (!points.allFinite())
          throw std::runtime_error(path.string() + ": object '" + name + "' deforms to non-finite points");
      }
      return format("scene, %zu objects, %zu lattices", scene.objects().size(),
                    scene.widgets.widgets(widgets::WidgetType::Lattice).size()) +
             foldNote(scene.widgets);
    }
    case FileKind::Widgets: {
      const widgets::WidgetModel model = readWidgetsFile(path, read);
      for (auto lattice : model.widgets(widgets::WidgetType::Lattice)) (void)model.ffdLattice(lattice);
      return format("widget file, %zu lattices, %zu affine widgets", model.widgets(widgets::WidgetType::Lattice).size(),
                    model.widgets(widgets::WidgetType::Affine).size()) +
             foldNote(model);
    }
    case FileKind::Mesh: {
      const scenes::MeshData mesh = readMeshFile(path, read);
      scenes::validateMesh(mesh, path.string());
      return format("mesh, %lld points", static_cast<long long>(mesh.points.rows()));
    }
  }
  return {};
}

int runValidate(const Args& args) {
  if (args.positional().empty()) throw UsageError("validate takes one or more FILEs");
  const Console console(args.flag("quiet"), false, false);
  const ReadSettings read = readSettings(args);  // a malformed limit: a usage error before any file
  int broken = 0;
  for (const auto& file : args.positional()) {
    try {
      const std::string summary = check(file, read);
      console.say(file + ": ok (" + summary + ")");
    } catch (const std::exception& e) {
      std::fflush(stdout);
      // Reader messages start with the file name; do not repeat it.
      const std::string message = e.what();
      if (message.rfind(file, 0) == 0 || message.find(fs::path(file).filename().string()) != std::string::npos)
        std::fprintf(stderr, "%s\n", message.c_str());
      else
        std::fprintf(stderr, "%s: %s\n", file.c_str(), message.c_str());
      ++broken;
    }
  }
  if (broken > 0) {
    std::fflush(stdout);
    std::fprintf(stderr, "%d of %zu files broken\n", broken, args.positional().size());
  }
  return broken == 0 ? 0 : 1;
}

}  // namespace

Command infoCommand() {
  return {"info",
          "summarise scene, widget and mesh files",
          "ffdkit-cli info FILE...\n       ffdkit-cli info --generators",
          "FILE: a scene (.json or a sample-scene folder), a widget file (.json with format\n"
          "\"ffdkit-widgets\") or a mesh / point file. Lists objects, lattices, affine widgets (the\n"
          "names --set takes) with their variations, attachments, and evaluates a scene. A volume mesh\n"
          "(an OpenFOAM case or polyMesh folder, .msh, .su2, .unv, .nodes, .k, .mdpa): its counts, patches,\n"
          "markers or physical groups; --quality adds the cell check (OpenFOAM: volumes, face pyramids,\n"
          "non-orthogonality, skewness; Gmsh and SU2: volumes and corner Jacobians), --widgets TOOL the\n"
          "same check after TOOL deforms it. A decomposed OpenFOAM case (processor* folders): each\n"
          "processor mesh's counts (and --quality its cell check), then the totals.\n",
          withReadOptions({{"generators", '\0', "", "list the registered curve and surface generators"},
                           {"quality", '\0', "", "a volume mesh: print its cell check"},
                           {"widgets", 'w', "TOOL", "a volume mesh: also check its cells as TOOL deforms them"},
                           quietOption()}),
          runInfo};
}

Command validateCommand() {
  return {"validate",
          "check scene, widget and mesh files; report every broken one",
          "ffdkit-cli validate FILE...",
          "Reads each file completely (a scene: its mesh files, generators, widgets and\n"
          "attachments, then evaluates it; a volume mesh: the whole file and the check of its cells; a\n"
          "decomposed OpenFOAM case: every processor mesh and its cells)\n"
          "and prints 'FILE: ok' or the problem, with line and\n"
          "column for malformed JSON. Exit status 1 when any file is broken. Writes nothing.\n",
          withReadOptions({quietOption()}),
          runValidate};
}

}  // namespace ffdkit::cli
