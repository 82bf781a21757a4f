// ffdkit-cli plot: curvature (and torsion) of a generated curve against arc length, as a PNG.
// Built into the VTK module (modules.h); the command and its options are vtk_commands.cpp.
#include "commands.h"
#include "module_functions.h"
#include "console.h"
#include "ffdkit/render/curve_plot.h"
#include "ffdkit/scenes/generator.h"
#include "ffdkit/scenes/scene_file.h"

namespace ffdkit::cli {

namespace {

namespace fs = std::filesystem;

/// The profile of `name` at `density`, its points charged first to a budget of the read options'
/// limits as a scene's generated object is (--density can ask for more than the scene did).
/// @throws std::runtime_error naming `source` and the limit when its bound is over them.
scenes::CurvatureProfile boundedProfile(const scenes::GeneratorRegistry& registry, const std::string& name,
                                        const scenes::GeneratorParameters& parameters, double density,
                                        const ReadSettings& read, const std::string& source) {
  const scenes::Generator& generator = registry.get(name);
  if (generator.pointBound) {
    meshio::ReadBudget budget(read.limits);
    const std::uint64_t points = generator.pointBound(parameters, density);
    try {
      budget.chargePoints(points, "generator '" + name + "'");
      budget.chargeBytes(points, scenes::kGeneratedBytesPerPoint, "generator '" + name + "' samples");
    } catch (const meshio::ReadLimitError& e) {
      throw std::runtime_error(source + ": " + e.what());
    }
  }
  return registry.profile(name, parameters, density);
}

}  // namespace

int runPlot(const Args& args) {
  Console console(args.flag("quiet"), args.flag("progress"), args.flag("timings"));
  const auto output = args.value("output");
  if (!output) throw UsageError("missing --output (-o) PLOT.png");
  app::CurvePlotOptions options;
  if (auto size = args.value("size")) parseSize(*size, "--size", options.width, options.height);
  double density = args.value("density") ? parseNumber(*args.value("density"), "--density") : 1.0;
  if (!(density > 0.0 && density <= 64.0)) throw UsageError("--density must be in (0, 64]");
  const auto generator = args.value("generator");
  const auto object = args.value("object");
  const auto& registry = scenes::builtinGenerators();
  const ReadSettings read = readSettings(args);

  scenes::CurvatureProfile profile;
  if (generator) {
    if (object || args.positional().size() != 1)
      throw UsageError("--generator NAME takes one PARAMETERS.json (a JSON object) and no --object");
    console.begin("read", "reading " + args.positional()[0]);
    const scenes::GeneratorParameters parameters = scenes::readGeneratorParameters(fs::path(args.positional()[0]));
    console.begin("profile", "sampling " + *generator);
    profile = boundedProfile(registry, *generator, parameters, density, read, args.positional()[0]);
    options.title = *generator;
  } else {
    if (!object || args.positional().size() != 1) throw UsageError("plot takes a SCENE and --object NAME (or --generator)");
    console.begin("read", "reading " + args.positional()[0]);
    const scenes::Scene scene = readSceneFile(fs::path(args.positional()[0]), read);
    const scenes::SceneObject* found = scene.findObject(*object);
    if (!found) {
      std::string known;
      for (const auto& o : scene.objects()) known += (known.empty() ? "" : ", ") + o.name;
      throw std::runtime_error(args.positional()[0] + ": no object '" + *object + "' (objects: " + known + ")");
    }
    const auto* generated = std::get_if<scenes::GeneratedSource>(&found->source);
    if (!generated)
      throw std::runtime_error("object '" + *object + "' is " +
                               (std::holds_alternative<scenes::PrimitiveOptions>(found->source) ? "a primitive"
                                                                                                 : "read from a mesh file") +
                               ", not a generated curve: only curve generators have a curvature profile");
    console.begin("profile", "sampling " + generated->generator);
    if (!args.value("density")) density = generated->density;
    profile = boundedProfile(registry, generated->generator, generated->parameters, density, read,
                             args.positional()[0] + ": object '" + *object + "'");
    options.title = *object + " (" + generated->generator + ")";
  }
  if (auto title = args.value("title")) options.title = *title;
  console.begin("plot", "plotting");
  app::plotCurvatureToPng(profile, *output, options);
  console.end();
  console.say("wrote " + *output + " (" + std::to_string(profile.arcLength.size()) + " samples" +
              (profile.torsion.size() != 0 ? ", curvature and torsion)" : ", curvature)"));
  console.printTimings();
  return 0;
}

}  // namespace ffdkit::cli
