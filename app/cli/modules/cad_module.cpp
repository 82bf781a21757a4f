// ffdkit-cli's OpenCASCADE module (modules.h): deform's STEP and IGES inputs and outputs, and the
// reader of scenes' CAD objects, with everything of OpenCASCADE they load. Its one exported symbol
// is the entry point.
#include "ffdkit/cad_scene/scene_cad_objects.h"
#include "ffdkit/meshio/vtk_writer.h"
#include "src/module_functions.h"
#include "src/modules.h"

namespace {

/// The program's .vtp and legacy .vtk writer (ModuleHost).
std::string (*programVtkWriter)(const ffdkit::meshio::MeshData&, bool) = nullptr;

ffdkit::meshio::MeshData readCadObject(const std::filesystem::path& path, ffdkit::meshio::ReadBudget& budget) {
  return ffdkit::cad_scene::readCadObject(path, budget);
}

void fillCadModule(const ffdkit::cli::ModuleHost& host, ffdkit::cli::CadModule& table) {
  programVtkWriter = host.vtkPolyDataBytes;
  // The scenes this module reads itself (deform --scene ... -o part.step) take their parts here.
  ffdkit::cad_scene::registerCadObjectReader();
  table.deformCadInput = ffdkit::cli::deformCadInput;
  table.deformSceneCadObject = ffdkit::cli::deformSceneCadObject;
  table.readCadObject = readCadObject;
}

}  // namespace

// meshio's hook (ffdkit/meshio/vtk_writer.h): this module's meshio writes .vtp and .vtk through
// the program, so that the module links no VTK.
std::string ffdkit::meshio::vtkPolyDataBytes(const MeshData& mesh, bool xml) {
  if (programVtkWriter == nullptr) throw MeshIoError("ffdkit-cli's OpenCASCADE module was given no VTK writer");
  return programVtkWriter(mesh, xml);
}

// The entry point (modules.h): the one symbol the module exports.
extern "C" __attribute__((visibility("default"))) int ffdkit_cli_cad_module(int version, std::size_t tableSize,
                                                                            const ffdkit::cli::ModuleHost* host, void* table) {
  return ffdkit::cli::fillModuleTable<ffdkit::cli::CadModule>(version, tableSize, host, table, fillCadModule);
}
