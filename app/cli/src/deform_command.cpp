// ffdkit-cli deform: applies a widget file or a scene's widget trees to meshes or point files.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <stdexcept>

#include "batch_ranks.h"
#include "cad_input.h"
#include "commands.h"
#include "console.h"
#include "decomposed_case.h"
#include "ffdkit/meshio/atomic_write.h"
#include "ffdkit/meshio/mesh_io.h"
#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/lattice_fit.h"
#include "frames.h"
#include "shape_guard.h"
#include "split_input.h"
#include "volume_mesh.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/scene_file.h"
#include "ffdkit/scenes/volume_object.h"
#include "ffdkit/scenes/widget_file.h"

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

/// The bounding box of every point of the scene's objects on every rank of the batch (min and
/// max do not depend on the order, so a batch fits exactly as one process does).
Eigen::AlignedBox3d objectsBox(const scenes::Scene& scene, const BatchRanks& ranks) {
  Eigen::AlignedBox3d box;
  for (const auto& object : scene.objects()) {
    if (object.mesh.points.rows() == 0) continue;
    box.extend(Eigen::AlignedBox3d(object.mesh.points.colwise().minCoeff().transpose(),
                                   object.mesh.points.colwise().maxCoeff().transpose()));
  }
  return ranks.unite(box);
}

/// --fit: one scale-and-translate map M takes the tool's rest box onto the objects' bounding
/// box fitted as every lattice is (scenes::fittedLatticeBox: grown by `padding` x its diagonal on
/// every side, a minimum thickness); every root frame F becomes M * F, so a tool of several
/// root lattices keeps its arrangement.
void fitRoots(scenes::Scene& scene, const Eigen::AlignedBox3d& objects, double padding) {
  const Eigen::AlignedBox3d tool = restBox(scene.widgets);
  if (objects.isEmpty() || tool.isEmpty()) throw std::runtime_error("--fit: nothing to fit (no points or no lattice)");
  if (!(objects.diagonal().norm() > 0.0)) throw std::runtime_error("--fit: the inputs' bounding box is a single point");
  const Eigen::Vector3d size = scenes::fittedLatticeBox(objects, padding).sizes();
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

/// Writes every output of every rank or none: each mesh is staged in a hidden temporary file
/// beside its target, and only when all ranks have staged all theirs are they renamed onto their
/// targets (a failure or a kill before that leaves every target as it was; the next write of a
/// target removes temporaries its killed writers left).
void writeAll(const std::vector<std::pair<fs::path, scenes::MeshData>>& outputs, const BatchRanks& ranks) {
  std::vector<meshio::StagedFile> staged;
  onEveryRank(ranks, [&] {
    for (const auto& [target, mesh] : outputs) staged.push_back(meshio::stageMesh(target, mesh));
  });
  for (auto& file : staged) file.commit();
}

/// The widget file, read once (by rank 0 of a batch) and sent to every rank.
widgets::WidgetModel readTool(const fs::path& path, const ReadSettings& read, const BatchRanks& ranks) {
  std::string text, error;
  if (ranks.leader()) {
    std::ifstream in(path, std::ios::binary);
    if (!in) error = path.string() + ": cannot open the widget file for reading";
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  ranks.broadcast(error);
  if (!error.empty()) throw scenes::WidgetFileError(error);
  ranks.broadcast(text);
  std::istringstream in(text);
  scenes::WidgetReadOptions options;
  options.limits = read.limits;
  return scenes::readWidgetFile(in, path.string(), options);
}

/// The INPUT pieces this rank reads, deforms and writes: a contiguous share of the list.
std::pair<std::size_t, std::size_t> ownPieces(std::size_t pieces, const BatchRanks& ranks) {
  const std::size_t size = static_cast<std::size_t>(ranks.size());
  const std::size_t rank = static_cast<std::size_t>(ranks.rank());
  return {rank * pieces / size, (rank + 1) * pieces / size};
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
  ReadSettings read;                 ///< --max-memory, --max-points, --allow-outside
  std::optional<std::string> frame;  ///< --frame T: the scene's animation at frame T
  bool allowInverted = false;        ///< --allow-inverted: write a volume mesh with bad cells
  bool quality = false;              ///< --quality: a volume mesh's cell check before and after
  ffd::Precision precision = ffd::Precision::Double;  ///< --precision
  ShapeGuardRequest guard;           ///< --keep-volume, --keep-centre, --fold-check

  /// The folder the scene's relative paths resolve against (the scene file's, or the sample's).
  fs::path sceneFolder() const {
    if (!sceneFile) return ".";
    if (fs::is_directory(*sceneFile)) return *sceneFile;
    return sceneFile->has_parent_path() ? sceneFile->parent_path() : fs::path(".");
  }
};

/// A scene object that is a volume mesh (scenes/volume_object.h), deformed: written by
/// pass-through in its own format after its cells are checked.
struct VolumeOutput {
  scenes::SceneObject object;  ///< its source (its mesh moved out)
  Eigen::MatrixX3d points;     ///< every point of the mesh, deformed
  fs::path path;               ///< where it goes
};

DeformRequest parseRequest(const Args& args) {
  DeformRequest r;
  if (auto w = args.value("widgets")) r.widgetFile = *w;
  if (auto s = args.value("scene")) r.sceneFile = *s;
  r.inputs = args.positional();
  // `deform SCENE ...`: a first positional scene file or sample folder stands for --scene SCENE.
  if (!r.widgetFile && !r.sceneFile && !r.inputs.empty() && fs::exists(r.inputs.front()) &&
      fileKind(r.inputs.front()) == FileKind::Scene) {
    r.sceneFile = r.inputs.front();
    r.inputs.erase(r.inputs.begin());
  }
  if (r.widgetFile.has_value() == r.sceneFile.has_value())
    throw UsageError("give exactly one of --widgets FILE and --scene FILE");
  const auto output = args.value("output");
  if (!output) throw UsageError("missing --output (-o) PATH");
  r.output = *output;
  r.frame = args.value("frame");
  if (r.frame && r.widgetFile) throw UsageError("--frame animates a scene; a widget file has no animation");
  if (r.widgetFile && r.inputs.empty()) throw UsageError("--widgets needs at least one INPUT mesh or point file");
  r.fit = args.flag("fit");
  r.allowInverted = args.flag("allow-inverted");
  r.quality = args.flag("quality");
  r.read = readSettings(args);
  if (r.fit && r.inputs.empty()) throw UsageError("--fit fits the lattices to INPUT files; a scene's objects need none");
  if (auto padding = args.value("padding")) {
    if (!r.fit) throw UsageError("--padding only applies with --fit");
    r.padding = parseNumber(*padding, "--padding");
    if (r.padding < 0.0) throw UsageError("--padding must be >= 0");
  }
  if (auto precision = args.value("precision")) {
    if (*precision == "single") {
      r.precision = ffd::Precision::Single;
    } else if (*precision != "double") {
      throw UsageError("--precision must be single or double; got '" + *precision + "'");
    }
  }
  r.settings = parseSettings(args.values("set"));
  r.guard = parseShapeGuard(args);
  r.objects = args.values("object");
  if (!r.objects.empty() && !r.inputs.empty())
    throw UsageError("--object selects objects of a scene without INPUT files");
  if (auto f = args.value("format")) {
    std::string format = lower(*f);
    if (!format.empty() && format[0] == '.') format.erase(0, 1);
    const auto known = meshio::meshFormatOf("output." + format);
    if (!known || !meshio::isWritable(*known))
      throw UsageError("--format must be one of obj, ply, stl, vtp, vtk, xyz, npy; got '" + *f + "'");
    r.format = format;
  }
  return r;
}

/// Reads the tool or scene and the inputs (in a batch: this rank's pieces, or its slice of the one
/// INPUT into `split`), and builds the scene to evaluate: with INPUT files every root lattice
/// deforms every input. `sourceOf` receives each input object's file.
scenes::Scene loadScene(const DeformRequest& r, Console& console, const BatchRanks& ranks,
                        std::map<std::string, fs::path>& sourceOf, std::optional<SplitInput>& split,
                        std::optional<VolumeMeshInput>& volume, std::optional<DecomposedCaseInput>& decomposed) {
  scenes::Scene scene;
  onEveryRank(ranks, [&] {
    if (r.widgetFile) {
      console.begin("read", "reading " + r.widgetFile->string());
      scene.widgets = readTool(*r.widgetFile, r.read, ranks);
    } else {
      console.begin("read", "reading " + r.sceneFile->string());
      scene = readSceneFile(*r.sceneFile, r.read);
      if (r.frame) scenes::applyAnimationFrame(scene, parseFrame(*r.frame, scene.animation()));
    }
  });
  if (DecomposedCaseInput::applies(r.inputs)) {
    console.begin("read", "reading the processor meshes of " + r.inputs.front());
    onEveryRank(ranks, [&] { decomposed.emplace(fs::path(r.inputs.front()), r.read, ranks); });
  } else if (SplitInput::applies(r.inputs.size(), ranks)) {
    console.begin("read", "reading a slice of " + r.inputs.front() + " per process");
    split.emplace(fs::path(r.inputs.front()), r.read.limits, ranks);
  } else if (VolumeMeshInput::applies(r.inputs)) {
    console.begin("read", "reading the volume mesh " + r.inputs.front());
    volume.emplace(fs::path(r.inputs.front()), r.read);
    if (r.quality) console.say("cell check before: " + volume->check(volume->points()).summary);
  }
  onEveryRank(ranks, [&] {
    if (r.inputs.empty()) return;
    if (decomposed) {  // this rank's meshes of the case, one object each
      for (std::size_t i = 0; i < decomposed->ownCount(); ++i) {
        scenes::SceneObject object;
        object.name = decomposed->name(i);
        object.mesh.points = decomposed->takePoints(i);
        scene.addObject(std::move(object));
      }
      return;
    }
    // Names from the whole list, so that every rank names the pieces as one process does.
    std::vector<std::string> names;
    std::set<std::string> taken;
    for (const auto& input : r.inputs) names.push_back(uniqueName(fs::path(input).stem().string(), taken));
    const auto [first, last] = split ? std::pair<std::size_t, std::size_t>(0, 1) : ownPieces(r.inputs.size(), ranks);
    std::vector<scenes::SceneObject> objects;
    for (std::size_t i = first; i < last; ++i) {
      const std::string& input = r.inputs[i];
      scenes::SceneObject object;
      if (split) {
        object.mesh.points = split->takePoints();
      } else if (volume) {
        object.mesh.points = volume->takePoints();
      } else {
        console.begin("read", "reading " + input);
        object.mesh = readMeshFile(fs::path(input), r.read);
      }
      object.name = names[i];
      object.source = scenes::MeshFileSource{fs::absolute(input).string()};
      sourceOf[object.name] = input;
      objects.push_back(std::move(object));
    }
    while (!scene.objects().empty()) scene.removeObject(scene.objects().back().name);
    for (scenes::SceneObject& object : objects) scene.addObject(std::move(object));
  });

  console.begin("build scene", "building the scene");
  const Eigen::AlignedBox3d box = r.fit ? objectsBox(scene, ranks) : Eigen::AlignedBox3d();
  onEveryRank(ranks, [&] {
    if (!r.inputs.empty()) {
      std::vector<scenes::Attachment> attachments;
      for (auto root : scene.widgets.roots()) {
        scenes::Attachment attachment{root, {}};
        for (const auto& object : scene.objects()) attachment.objects.push_back(object.id);
        attachments.push_back(std::move(attachment));
      }
      scene.setAttachments(std::move(attachments));
      if (scene.attachments().empty()) console.warn("the widget model has no lattice: the output equals the input");
    }
    if (r.fit) fitRoots(scene, box, r.padding);
    applySettings(scene.widgets, r.settings);
    scenes::validateScene(scene);
  });
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
    for (const auto& object : scene.objects()) names.push_back(object.name);
  for (const auto& name : names)
    if (!scene.findObject(name)) throw std::runtime_error("--object: the scene has no object '" + name + "'");
  // In a batch a rank holds only its pieces (possibly none): decide as for the whole list.
  const std::size_t total = r.inputs.empty() ? names.size() : r.inputs.size();
  if (total == 0) throw std::runtime_error("nothing to deform: the scene has no objects");
  intoFolder = total > 1 || fs::is_directory(r.output);
  std::vector<Output> targets;
  for (const auto& name : names) {
    // A scene's volume mesh goes to -o itself, or into the folder by its name and its file's
    // extension (an OpenFOAM case: a folder of its name).
    if (r.inputs.empty() && scenes::volumeMeshFormatOf(scene.findObject(name)->source, r.sceneFolder())) {
      const fs::path source(std::get<scenes::MeshFileSource>(scene.findObject(name)->source).path);
      const bool folderCase = fs::is_directory(source.is_absolute() ? source : r.sceneFolder() / source);
      // One result goes to -o even when it is an existing folder (an OpenFOAM case written before).
      const bool single = total == 1;
      targets.push_back({name, single ? r.output : r.output / (name + (folderCase ? "" : lower(source.extension().string())))});
      continue;
    }
    if (!intoFolder) {
      if (r.output.extension().empty())
        throw UsageError("-o " + r.output.string() + ": no extension to pick a format by");
      targets.push_back({name, r.output});
      continue;
    }
    std::string ext = r.format.value_or("");
    if (ext.empty() && sourceOf.count(name)) ext = lower(sourceOf.at(name).extension().string());
    if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
    if (ext.empty() || ext == "gltf" || ext == "glb")
      throw UsageError("give --format EXT for object '" + name + "' (its input format cannot be written)");
    targets.push_back({name, r.output / (name + "." + ext)});
  }
  return targets;
}

/// Evaluates the scene once, with the same result as scenes::deformScene: every lattice is
/// embedded and the points deformed in one pass; the pipelines take the objects' points over
/// (the scene's meshes keep their faces). The embedding's share of it (the pipeline times it) is
/// reported as "embed", the rest (syncing the lattices, deforming) as "deform".
void evaluate(scenes::Scene& scene, scenes::SceneDeformer& deformer, Console& console) {
  Eigen::Index pointCount = 0;
  for (const auto& object : scene.objects()) pointCount += object.mesh.points.rows();
  console.begin("deform", "embedding and deforming " + std::to_string(pointCount) + " points");
  deformer.evaluateTakingPoints(scene);
  console.carve("embed", 1e3 * deformer.lastStats().embedSeconds);
}

/// Writes the scene's deformed volume meshes by pass-through, all or nothing: every one's cells
/// are checked first (a bad one refuses them all with the count and first ids, unless
/// --allow-inverted), then all are written (scenes::writeVolumeObjects). They are written before
/// the other outputs, so that a refused volume mesh leaves the surface outputs unwritten too.
void writeVolumeOutputs(const std::vector<VolumeOutput>& outputs, const DeformRequest& r, Console& console) {
  if (outputs.empty()) return;
  scenes::VolumeObjectWriteOptions options;
  options.allowInverted = r.allowInverted;
  options.confinement = r.read.confinement;
  options.limits = r.read.limits;
  std::vector<scenes::VolumeObjectOutput> batch;
  for (const VolumeOutput& output : outputs) batch.push_back({&output.object, &output.points, output.path});
  console.begin("write", "checking and writing " + std::to_string(outputs.size()) + " volume mesh(es)");
  const std::vector<scenes::VolumeObjectWriteResult> results = scenes::writeVolumeObjects(batch, r.sceneFolder(), options);
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const VolumeOutput& output = outputs[i];
    const scenes::VolumeObjectWriteResult& result = results[i];
    if (r.quality) console.say("cell check after: " + result.quality.summary);
    if (!result.quality.ok()) console.warn("wrote a mesh with " + result.quality.badText + " (--allow-inverted)");
    console.say("wrote " + output.path.string() + " (" + meshio::volumeMeshFormatName(result.format) + ", " +
                std::to_string(result.pointCount) + " points, " + std::to_string(result.quality.cellCount) + " cells" +
                (result.quality.checked && result.quality.ok() ? ", all valid)" : ")"));
  }
}

int runDeform(const Args& args) {
  if (isCadDeform(args)) return runCadDeform(args);  // a STEP or IGES part: the B-rep path (cad_input.cpp)
  if (isCadSceneDeform(args)) return runCadSceneDeform(args);  // a scene's STEP part written as STEP
  // In an mpirun batch every rank runs this; rank 0 speaks for the batch.
  // Static: MPI_Finalize (a fence of every rank) runs after main has printed this rank's error, so
  // that no rank exits, and mpirun kills the others, before every failing rank has said why.
  static const BatchRanks ranks;
  Console console(args.flag("quiet") || !ranks.leader(), args.flag("progress") && ranks.leader(),
                  args.flag("timings") && ranks.leader());
  DeformRequest request;
  onEveryRank(ranks, [&] {
    request = parseRequest(args);
    if (ranks.size() > 1 && !DecomposedCaseInput::applies(request.inputs) && VolumeMeshInput::applies(request.inputs))
      throw UsageError("an mpirun batch does not take an OpenFOAM case yet: run one process on the reconstructed case");
    if (ranks.size() > 1 && (!request.widgetFile || request.inputs.empty()))
      throw UsageError("an mpirun batch takes --widgets TOOL and INPUT pieces (each rank deforms its share) "
                       "or one INPUT (each rank deforms its slice)");
  });
  std::map<std::string, fs::path> sourceOf;
  std::optional<SplitInput> split;
  std::optional<VolumeMeshInput> volume;
  std::optional<DecomposedCaseInput> decomposed;
  scenes::Scene scene = loadScene(request, console, ranks, sourceOf, split, volume, decomposed);
  bool intoFolder = false;
  std::vector<Output> targets;
  onEveryRank(ranks, [&] {
    // A volume mesh is written as a folder: -o names it.
    if (decomposed) {  // written as one folder too: -o names it
      for (std::size_t i = 0; i < decomposed->ownCount(); ++i) targets.push_back({decomposed->name(i), request.output});
    } else {
      targets = volume ? std::vector<Output>{{scene.objects().front().name, request.output}}
                       : plannedOutputs(request, scene, sourceOf, intoFolder);
    }
    if (split) split->checkTarget(targets.front().path);
  });
  scenes::SceneDeformer deformer;
  deformer.setPrecision(request.precision);
  std::vector<std::pair<fs::path, scenes::MeshData>> meshes;
  std::vector<VolumeOutput> volumeOutputs;
  std::map<std::string, scenes::MeshData> restOf;  // the objects whose shape is kept, before deforming
  InPlaceDeformCounts inPlaceCounts;  // a volume mesh deformed in place (deformVolumeInPlace)
  onEveryRank(ranks, [&] {
    checkFoldsBeforeDeform(scene.widgets, request.guard.foldCheck, console);
    for (const auto* names : {&request.guard.keepVolume, &request.guard.keepCentre})
      for (const auto& name : *names) {
        const auto* object = scene.findObject(name);
        if (!object) throw std::runtime_error("--keep-volume/--keep-centre: no object '" + name + "' to deform");
        restOf.emplace(name, object->mesh);
      }
    // A volume mesh under one lattice is deformed in place: the same points as the scene
    // deformer's, without an embedding or a second copy of a mesh of millions of points.
    const bool inPlace = volume && targets.size() == 1 && !request.guard.keeps(targets.front().object) &&
                         deformsByOneLattice(scene, targets.front().object);
    Eigen::MatrixX3d deformedInPlace;
    if (inPlace) {
      deformedInPlace = scene.takeObjectPoints(targets.front().object);
      inPlaceCounts = deformVolumeInPlace(scene, targets.front().object, deformedInPlace, request.precision, console);
    } else {
      evaluate(scene, deformer, console);
    }
    for (const auto& target : targets) {
      // Both are done with the object: take its mesh (its points are in the deformer) and its
      // deformed points (no copies).
      scenes::SceneObject taken = scene.takeObject(target.object);
      scenes::MeshData mesh = std::move(taken.mesh);
      mesh.points = inPlace ? std::move(deformedInPlace) : deformer.takePoints(target.object);
      if (request.guard.keeps(target.object)) {
        const auto& keep = request.guard;
        restoreShape(target.object, restOf.at(target.object), mesh.points,
                     std::count(keep.keepVolume.begin(), keep.keepVolume.end(), target.object) > 0,
                     std::count(keep.keepCentre.begin(), keep.keepCentre.end(), target.object) > 0, console);
      }
      // A whole file is checked by its writer (stageMesh); a rank's slice of a split INPUT is
      // checked here, unless empty (more ranks than points or lines).
      if (split && mesh.points.rows() > 0) scenes::validateMesh(mesh, "deformed object '" + target.object + "'");
      if (request.inputs.empty() && scenes::volumeMeshFormatOf(taken.source, request.sceneFolder())) {
        volumeOutputs.push_back({std::move(taken), std::move(mesh.points), target.path});
        continue;
      }
      meshes.emplace_back(target.path, std::move(mesh));
    }
  });
  const scenes::SceneDeformStats stats = deformer.lastStats();
  if (!volume && !decomposed) console.begin("write", "writing " + std::to_string(split ? 1 : meshes.size()) + " file(s)");
  if (decomposed) {
    console.begin("write", "checking and writing " + std::to_string(decomposed->totalCount()) + " meshes of " +
                               request.inputs.front());
    std::vector<const Eigen::MatrixX3d*> deformedPoints;
    for (const auto& [path, mesh] : meshes) deformedPoints.push_back(&mesh.points);
    decomposed->write(deformedPoints, request.output, request.allowInverted, console, ranks);
    console.end();
    console.say("wrote " + request.output.string() + " (" + std::to_string(decomposed->totalCount()) + " meshes of a " +
                "decomposed case, " + std::to_string(ranks.size()) + " process(es))");
  } else if (volume) {
    const auto& [path, mesh] = meshes.front();
    const meshio::VolumeMeshQuality quality =
        volume->checkAndWrite(mesh.points, path, request.allowInverted, request.quality, console);
    console.end();
    console.say("wrote " + path.string() + " (" + std::to_string(mesh.points.rows()) + " points, " +
                std::to_string(quality.cellCount) + " cells" + (quality.ok() ? ", all valid)" : ")"));
  } else if (split) {
    split->write(meshes.front().first, meshes.front().second.points, ranks);
    console.end();
    console.say("wrote " + meshes.front().first.string() + " (" + std::to_string(split->totalPoints()) + " points, a slice from each of " +
                std::to_string(ranks.size()) + " processes)");
  } else {
    if (intoFolder) fs::create_directories(request.output);
    writeVolumeOutputs(volumeOutputs, request, console);
    writeAll(meshes, ranks);
    console.end();
    for (const auto& [path, mesh] : meshes)
      console.say("wrote " + path.string() + " (" + std::to_string(mesh.points.rows()) + " points)");
  }
  if (ranks.size() > 1 && !split && !decomposed) console.say("mpirun batch: " + std::to_string(ranks.size()) + " processes wrote " +
                                    std::to_string(ranks.sum(static_cast<std::int64_t>(meshes.size()))) + " file(s)");
  const std::int64_t failed = ranks.sum(stats.failedPoints + inPlaceCounts.failedPoints);
  const std::int64_t outside = ranks.sum(stats.outsidePoints + inPlaceCounts.outsidePoints);
  if (failed > 0) console.warn(std::to_string(failed) + " points failed to embed and were left unchanged");
  if (outside > 0)
    console.say(std::to_string(outside) + " points lie outside their lattice (outside policy applied)");
  console.printTimings();
  return 0;
}

std::vector<OptionSpec> withShapeGuardOptions(std::vector<OptionSpec> options) {
  for (OptionSpec& option : shapeGuardOptions()) options.push_back(std::move(option));
  return options;
}

}  // namespace

Command deformCommand() {
  return {"deform",
          "apply a widget file or a scene to meshes or point files and write the result",
          "ffdkit-cli deform --widgets TOOL.json INPUT... -o OUTPUT [options]\n"
          "       ffdkit-cli deform --scene SCENE [INPUT...] -o OUTPUT [--frame T] [options]\n"
          "       ffdkit-cli deform SCENE --frame T -o OUTPUT [options]",
          "With --widgets, every root lattice of the widget file deforms every INPUT where it lies\n"
          "(--fit first maps the lattices onto the inputs' bounding box). With --scene and INPUT\n"
          "files, the scene's root lattices deform the inputs the same way; without INPUT files\n"
          "the scene's own objects are deformed and written (--object picks some). A scene may also\n"
          "be given as the first INPUT. --frame T first sets the scene's animation to frame T (in its\n"
          "frame range; docs/animation.md); --set values apply after it.\n"
          "INPUT: .obj .ply .stl .vtp .vtk .gltf .glb .xyz .npy, or a volume mesh: an OpenFOAM case or\n"
          "polyMesh folder, .msh (Gmsh 4.1), .su2, .unv, .nodes (Elmer), .k/.key (LS-DYNA), .mdpa (Kratos).\n"
          "OUTPUT: a file when there is one result (its extension picks the format: .obj .ply .stl .vtp\n"
          ".vtk .xyz .npy), else a folder that receives NAME.EXT per object. Normals are recomputed when\n"
          "the input had them. A volume mesh is written to OUTPUT (an OpenFOAM case: a folder) with every\n"
          "byte but the point coordinates as read, after its cells are checked: inverted or zero-volume cells refuse\n"
          "the write unless --allow-inverted (docs/volume-meshes.md). A scene object whose file is a volume\n"
          "mesh is written the same way, whole, to an OUTPUT named for its format (.msh, a folder for a case).\n"
          "Nothing is written when anything fails.\n"
          "A STEP or IGES INPUT (.step .stp .iges .igs) is deformed as a B-rep by the tool's one Bernstein\n"
          "lattice, composed exactly with every surface (--cad-method), and written as STEP or IGES\n"
          "(-o part.step; docs/cad.md).\n"
          "--keep-volume OBJECT / --keep-centre OBJECT restore, after the deformation, the volume the\n"
          "object's closed surface enclosed and its centre, by the least-norm change of a correction\n"
          "lattice fitted around it (docs/cli.md). --fold-check warns (default) or fails when a lattice\n"
          "of the tool folds space over itself (a certified bound of det J per cell).\n"
          "Batch: mpirun -n N ffdkit-cli deform --widgets TOOL PIECE... -o FOLDER: rank 0 reads TOOL\n"
          "and sends it to every rank; each rank reads, deforms and writes its contiguous share of\n"
          "the PIECE files (--fit fits to the box of all pieces), as one process would (docs/scaling.md).\n"
          "With one INPUT (binary .ply, .npy, .xyz) each rank reads, deforms and writes its slice of\n"
          "the vertices into the one OUTPUT (.ply, .npy, .xyz); rank 0 also copies a PLY's faces.\n",
          withCadOptions(withShapeGuardOptions(withReadOptions({{"widgets", 'w', "FILE", "the widget file (deformation tool) to apply"},
           {"scene", 's', "SCENE", "the scene (file or sample folder) whose widget trees to apply"},
           {"output", 'o', "PATH", "output file, or folder for several outputs"},
           {"frame", '\0', "T", "with a scene: deform at frame T of its animation"},
           setOption(),
           {"fit", '\0', "", "refit the root lattices' frames to the inputs' bounding box"},
           {"padding", '\0', "P", "with --fit: margin on every side, relative to the box diagonal (0.05)"},
           {"object", '\0', "NAME", "with --scene and no INPUT: write only this object", true},
           {"format", '\0', "EXT", "format of outputs written into a folder (default: the input's)"},
           {"allow-inverted", '\0', "", "with a volume mesh: write it even when deformed cells are inverted or "
                                          "of zero volume (says how many)"},
           {"quality", '\0', "", "with a volume mesh: print the cell check before and after"},
           {"precision", '\0', "P", "double (default) or single: the displacements in float32, as Blender does "
                                     "(within 1e-6 of the largest control-point move; docs/ffd-engine.md)"},
           quietOption(), progressOption(), timingsOption()}))),
          runDeform};
}

}  // namespace ffdkit::cli
