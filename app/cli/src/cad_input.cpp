// ffdkit-cli deform with a STEP or IGES input, or a scene's CAD object written as STEP or IGES:
// their options and when deform takes this path. The work (the B-rep deformed by the cad module,
// docs/cad.md) is in the OpenCASCADE module (cad_deform.cpp, modules.h), loaded when it runs.
#include "cad_input.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "ffdkit/scenes/cad_objects.h"
#include "module_loader.h"

namespace ffdkit::cli {

namespace {

/// What a build without OpenCASCADE says (as cad_scene::CadUnavailableError).
constexpr const char* kWithoutCad =
    "this program was built without OpenCASCADE (FFDKIT_WITH_CAD=OFF), which ";

bool hasCadExtension(const std::string& path) { return scenes::isCadFile(path); }

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

bool isCadSceneDeform(const Args& args) {
  const auto output = args.value("output");
  return output && hasCadExtension(*output) && !args.value("widgets") && !isCadDeform(args) &&
         (args.value("scene") || args.positional().size() == 1);
}

int runCadDeform(const Args& args) {
  if (!cadModuleBuilt()) throw std::runtime_error(kWithoutCad + std::string("STEP and IGES inputs need"));
  return cadModule("deform with a STEP or IGES input").deformCadInput(args);
}

int runCadSceneDeform(const Args& args) {
  if (!cadModuleBuilt()) throw std::runtime_error(kWithoutCad + std::string("STEP and IGES outputs need"));
  return cadModule("deform writing STEP or IGES").deformSceneCadObject(args);
}

}  // namespace ffdkit::cli
