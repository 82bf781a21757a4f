// ffdkit-cli deform with a STEP or IGES input, or a scene's CAD object written as STEP or IGES: the
// B-rep deformed by the cad module (docs/cad.md). Built into the OpenCASCADE module (modules.h);
// the options and the choice of this path are cad_input.cpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

#include "commands.h"
#include "console.h"
#include "ffdkit/cad/cad_check.h"
#include "ffdkit/cad/cad_deform.h"
#include "ffdkit/cad/cad_io.h"
#include "ffdkit/cad_scene/scene_cad_objects.h"
#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/widget_file.h"
#include "frames.h"
#include "module_functions.h"
#include "read_options.h"

namespace ffdkit::cli {

namespace fs = std::filesystem;

namespace {

std::string fixed(double value, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

/// deform's --cad-* options, checked.
cad::CadDeformOptions cadOptions(const Args& args) {
  cad::CadDeformOptions options;
  if (auto method = args.value("cad-method")) {
    if (*method == "exact")
      options.method = cad::CadMethod::Exact;
    else if (*method == "poles")
      options.method = cad::CadMethod::Poles;
    else
      throw UsageError("--cad-method must be exact or poles, got '" + *method + "'");
  }
  if (auto degree = args.value("cad-degree-limit")) {
    const double value = parseNumber(*degree, "--cad-degree-limit");
    if (value != std::floor(value) || value < 1 || value > 25)
      throw UsageError("--cad-degree-limit must be an integer in [1, 25]");
    options.maxDegree = static_cast<int>(value);
  }
  if (auto tolerance = args.value("cad-tolerance")) {
    const double value = parseNumber(*tolerance, "--cad-tolerance");
    if (!(value > 0.0) || !std::isfinite(value)) throw UsageError("--cad-tolerance must be a number > 0");
    options.tolerance = value;
  }
  options.approximate = !args.flag("cad-exact-only");
  if (args.flag("cad-check")) options.samples = 9;
  return options;
}

/// Deforms `model` by `lattice`, writes it to `output` (STEP or IGES by extension) and says what
/// was done; returns the exit code (1 when --cad-check finds the result invalid).
int deformAndWrite(const cad::CadModel& model, const ffd::Lattice& lattice, const cad::CadDeformOptions& options,
                   const std::string& output, Console& console) {
  console.begin("deform", "deforming " + std::to_string(model.counts().faces) + " faces");
  const cad::CadDeformResult result = cad::deformCad(model, lattice, options);
  std::optional<cad::CadCheck> measured;
  if (options.samples > 0) {
    console.begin("check", "checking the result");
    measured = cad::checkModel(result.model);
  }
  console.begin("write", "writing " + output);
  cad::writeCad(result.model, output);
  console.end();
  const auto& report = result.report;
  console.say("wrote " + output + " (" + std::to_string(result.model.partCount()) + " part(s), " +
              std::to_string(report.faces) + " faces, " + std::to_string(report.edges) + " edges, degree up to " +
              std::to_string(report.maxDegree) + ", " +
              (options.method == cad::CadMethod::Poles       ? "poles moved"
               : report.approximations.empty() ? "exact composition"
                                               : "exact composition, " + std::to_string(report.approximatedFaces) +
                                                     " face(s) and " + std::to_string(report.approximatedEdges) +
                                                     " edge(s) approximated") +
              ")");
  if (!report.approximations.empty()) {
    console.say("approximated within " + fixed(report.tolerance, 3) + " of the FFD (largest deviation measured: " +
                fixed(report.approximationError, 3) + "):");
    const std::size_t shown = std::min<std::size_t>(report.approximations.size(), 10);
    for (std::size_t i = 0; i < shown; ++i) console.say("  " + report.approximations[i]);
    if (shown < report.approximations.size())
      console.say("  ... and " + std::to_string(report.approximations.size() - shown) + " more");
  }
  if (measured) {
    console.say("deviation from the FFD: " + fixed(report.maxDeviation, 3) + " (model size " +
                fixed(model.bounds().diagonal().norm(), 4) + "); largest edge-face gap: " + fixed(report.maxGap, 3) +
                "; largest tolerance: " + fixed(measured->maxTolerance, 3));
    console.say(std::string("BRepCheck: ") + (measured->valid ? "valid" : "INVALID, " + measured->firstProblem) +
                "; volume " + fixed(measured->volume, 8));
  }
  console.printTimings();
  return measured && !measured->valid ? 1 : 0;
}

}  // namespace

int deformCadInput(const Args& args) {
  Console console(args.flag("quiet"), args.flag("progress"), args.flag("timings"));
  const auto widgets = args.value("widgets");
  const auto output = args.value("output");
  const auto& inputs = args.positional();
  if (!widgets) throw UsageError("a STEP or IGES INPUT is deformed by a widget file: give --widgets TOOL.json");
  if (inputs.size() != 1) throw UsageError("a STEP or IGES INPUT is deformed alone: give exactly one INPUT");
  if (!output || !cad::cadFormatOf(*output))
    throw UsageError("a STEP or IGES INPUT is written as STEP or IGES: give -o OUTPUT.step (or .stp, .iges, .igs)");
  for (const char* unsupported : {"scene", "fit", "frame", "set", "keep-volume", "keep-centre"})
    if (args.flag(unsupported)) throw UsageError(std::string("--") + unsupported + " does not apply to a STEP or IGES INPUT yet");
  const cad::CadDeformOptions options = cadOptions(args);

  console.begin("read", "reading " + *widgets);
  scenes::WidgetReadOptions widgetOptions;
  widgetOptions.limits = readSettings(args).limits;
  const widgets::WidgetModel tool = scenes::readWidgetFile(fs::path(*widgets), widgetOptions);
  const auto roots = tool.roots();
  if (roots.size() != 1 || !tool.children(roots.front()).empty())
    throw std::runtime_error(*widgets + ": a STEP or IGES INPUT is deformed by one lattice; the tool has " +
                             std::to_string(roots.size()) + " root lattice(s) and child lattices are not supported yet");
  const ffd::Lattice lattice = tool.ffdLattice(roots.front());
  console.begin("read", "reading " + inputs.front());
  const cad::CadModel model = cad::readCad(inputs.front());
  return deformAndWrite(model, lattice, options, *output, console);
}

int deformSceneCadObject(const Args& args) {
  Console console(args.flag("quiet"), args.flag("progress"), args.flag("timings"));
  const std::string output = *args.value("output");
  const auto sceneOption = args.value("scene");
  const auto& inputs = args.positional();
  if (sceneOption && !inputs.empty())
    throw UsageError("a scene's CAD object written as STEP or IGES takes no INPUT files (the scene names the part)");
  const fs::path sceneFile = sceneOption ? fs::path(*sceneOption) : fs::path(inputs.front());
  for (const char* unsupported : {"fit", "keep-volume", "keep-centre", "format", "precision"})
    if (args.flag(unsupported))
      throw UsageError(std::string("--") + unsupported + " does not apply to a STEP or IGES output yet");
  const cad::CadDeformOptions options = cadOptions(args);
  const ReadSettings read = readSettings(args);

  console.begin("read", "reading " + sceneFile.string());
  scenes::Scene scene = readSceneFile(sceneFile, read);
  if (auto frame = args.value("frame")) scenes::applyAnimationFrame(scene, parseFrame(*frame, scene.animation()));
  applySettings(scene.widgets, parseSettings(args.values("set")));
  const std::vector<std::string> named = args.values("object");
  if (named.size() > 1) throw UsageError("a STEP or IGES output holds one CAD object: give at most one --object");
  const scenes::SceneObject* object = nullptr;
  if (!named.empty()) {
    object = scene.findObject(named.front());
    if (object == nullptr) throw std::runtime_error(sceneFile.string() + ": no object named '" + named.front() + "'");
    if (!cad_scene::isCadObject(*object))
      throw std::runtime_error(sceneFile.string() + ": object '" + named.front() +
                               "' is not read from a STEP or IGES file; -o " + output + " writes a CAD object");
  } else {
    const std::vector<const scenes::SceneObject*> found = cad_scene::cadObjects(scene);
    if (found.empty())
      throw std::runtime_error(sceneFile.string() + ": the scene has no object read from a STEP or IGES file; -o " +
                               output + " writes one (a mesh format writes the deformed meshes)");
    if (found.size() > 1)
      throw UsageError(sceneFile.string() + ": the scene has " + std::to_string(found.size()) +
                       " CAD objects: pick the one to write with --object NAME");
    object = found.front();
  }
  // The part's file, relative to the scene's folder (or a sample folder given as the scene).
  const fs::path folder = fs::is_directory(sceneFile) ? sceneFile
                          : sceneFile.has_parent_path() ? sceneFile.parent_path()
                                                        : fs::path(".");
  const fs::path part = cad_scene::cadObjectFile(*object, folder);
  const std::optional<widgets::WidgetId> lattice = cad_scene::cadObjectLattice(scene, *object);
  console.begin("read", "reading " + part.string());
  const cad::CadModel model = cad::readCad(part);
  if (!lattice) {
    console.begin("write", "writing " + output);
    cad::writeCad(model, output);
    console.end();
    console.say("wrote " + output + " as read: no lattice deforms '" + object->name + "'");
    return 0;
  }
  return deformAndWrite(model, scene.widgets.ffdLattice(*lattice), options, output, console);
}

}  // namespace ffdkit::cli
