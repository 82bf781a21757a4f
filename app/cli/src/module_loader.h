#pragma once
// Finding and loading ffdkit-cli's modules (modules.h) at first use.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "modules.h"

namespace ffdkit::cli {

/// A module that cannot be found or loaded. what(): "cannot load ffdkit-cli's VTK module
/// <file>, which <what needs it> needs: <why>".
class ModuleLoadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Where the module `file` is looked for, in order: the folder of the running program (the build
/// tree), then FFDKIT_CLI_MODULE_DIR relative to it (the install tree's lib/ffdkit). The program's
/// folder comes from /proc/self/exe, never from the working directory.
std::vector<std::filesystem::path> moduleCandidates(const std::string& file);

/// The VTK module's table, loaded (once) at the first call. `need` says what needs it, for the
/// error ("render", "writing a .vtp or .vtk file").
/// @throws ModuleLoadError when the module is missing, cannot be loaded, has no entry point or
///         comes from another build.
const VtkModule& vtkModule(const std::string& need);

/// The OpenCASCADE module's table, as vtkModule.
const CadModule& cadModule(const std::string& need);

/// Whether this build has the OpenCASCADE module (FFDKIT_WITH_CAD). The one place the program
/// asks: only this file is compiled with the answer (FFDKIT_HAS_CAD), so that the program's other
/// files compile the same with and without OpenCASCADE (and the no-VTK build takes them from
/// the compiler cache).
bool cadModuleBuilt();

/// With the OpenCASCADE module: scenes naming STEP or IGES parts read them through it
/// (scenes::setCadMeshReader with readCadObjectThroughModule), loaded at the first one.
/// Without it: nothing, and the scenes refuse such parts.
void installCadMeshReader();

/// Reads a scene's STEP or IGES object through the OpenCASCADE module (loaded at the first one);
/// a ModuleLoadError then becomes a meshio::MeshIoError naming the file.
meshio::MeshData readCadObjectThroughModule(const std::filesystem::path& path, meshio::ReadBudget& budget);

}  // namespace ffdkit::cli
