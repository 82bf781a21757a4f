// ffdkit-cli's VTK module (modules.h): render, plot, and meshio's .vtp and legacy .vtk writer,
// with everything of VTK they load. Its one exported symbol is the entry point.
#include "ffdkit/meshio/vtk_writer.h"
#include "ffdkit/scenes/cad_objects.h"
#include "src/module_functions.h"
#include "src/modules.h"

namespace {

void fillVtkModule(const ffdkit::cli::ModuleHost& host, ffdkit::cli::VtkModule& table) {
  // The scenes this module reads take their STEP and IGES parts through the program's reader.
  if (host.readCadObject != nullptr) ffdkit::scenes::setCadMeshReader(host.readCadObject);
  table.render = ffdkit::cli::runRender;
  table.plot = ffdkit::cli::runPlot;
  table.polyDataBytes = ffdkit::meshio::vtkPolyDataBytes;
}

}  // namespace

// The entry point (modules.h): the one symbol the module exports.
extern "C" __attribute__((visibility("default"))) int ffdkit_cli_vtk_module(int version, std::size_t tableSize,
                                                                            const ffdkit::cli::ModuleHost* host, void* table) {
  return ffdkit::cli::fillModuleTable<ffdkit::cli::VtkModule>(version, tableSize, host, table, fillVtkModule);
}
