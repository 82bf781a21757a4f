// ffdkit-cli deform with a STEP or IGES input: the B-rep deformed by the cad module (docs/cad.md).
#include "cad_input.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

#include "console.h"
#include "ffdkit/scenes/widget_file.h"
#include "read_options.h"

#if FFDKIT_HAS_CAD
#include "ffdkit/cad/cad_check.h"
#include "ffdkit/cad/cad_deform.h"
#include "ffdkit/cad/cad_io.h"
#endif

namespace ffdkit::cli {

namespace {

namespace fs = std::filesystem;

bool hasCadExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".step" || ext == ".stp" || ext == ".iges" || ext == ".igs";
}

std::string fixed(double value, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

}  // namespace

std::vector<OptionSpec> withCadOptions(std::vector<OptionSpec> options) {
  options.push_back({"cad-method", '\0', "M", "STEP/IGES input: exact (default; the FFD composed with every surface) or "
                                              "poles (each NURBS pole moved, PyGeM's method: gaps, not the FFD)"});
  options.push_back({"cad-degree-limit", '\0', "N", "STEP/IGES input, exact: the highest degree per direction a composed "
                                                   "surface or curve may have; above it the FFD is approximated (15, at most 25)"});
  options.push_back({"cad-tolerance", '\0', "T", "STEP/IGES input, exact: the largest deviation from the FFD an approximated "
                                                "surface or curve may have, in model units (1e-6 x the model's size)"});
  options.push_back({"cad-exact-only", '\0', "", "STEP/IGES input: refuse what cannot be composed exactly (a degree above the "
                                                "limit, a B-spline lattice's knot plane crossed across a face's parameter "
                                                "lines, a part leaving the lattice) instead of approximating it"});
  options.push_back({"cad-check", '\0', "", "STEP/IGES input: measure the result (deviation from the FFD, gaps, "
                                            "BRepCheck validity, volume) and print it"});
  return options;
}

bool isCadDeform(const Args& args) {
  const auto& inputs = args.positional();
  return std::any_of(inputs.begin(), inputs.end(), hasCadExtension);
}

#if FFDKIT_HAS_CAD

int runCadDeform(const Args& args) {
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
  const bool check = args.flag("cad-check");
  if (check) options.samples = 9;

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
  console.begin("deform", "deforming " + std::to_string(model.counts().faces) + " faces");
  const cad::CadDeformResult result = cad::deformCad(model, lattice, options);
  std::optional<cad::CadCheck> measured;
  if (check) {
    console.begin("check", "checking the result");
    measured = cad::checkModel(result.model);
  }
  console.begin("write", "writing " + *output);
  cad::writeCad(result.model, *output);
  console.end();
  const auto& report = result.report;
  console.say("wrote " + *output + " (" + std::to_string(result.model.partCount()) + " part(s), " +
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

#else

int runCadDeform(const Args&) {
  throw std::runtime_error("this ffdkit-cli was built without OpenCASCADE (FFDKIT_WITH_CAD=OFF), which STEP and IGES "
                           "inputs need");
}

#endif

}  // namespace ffdkit::cli
