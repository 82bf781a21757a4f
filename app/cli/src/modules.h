#pragma once
// ffdkit-cli's modules: the code of the commands that need VTK (render, plot, writing .vtp and
// legacy .vtk) or OpenCASCADE (STEP and IGES inputs and outputs, scenes' CAD objects), built as
// shared modules that ffdkit-cli loads with dlopen when a command first needs one
// (module_loader.h), so that every other command starts without loading either library.
// Each module exports one C entry point that fills a table of its functions; a module and the
// program come from one build, and the entry point refuses a table of another version or size.

#include <cstddef>
#include <filesystem>
#include <string>

#include "args.h"
#include "ffdkit/meshio/mesh_data.h"
#include "ffdkit/meshio/read_limits.h"

namespace ffdkit::cli {

/// Raised when the tables below change.
inline constexpr int kModuleInterfaceVersion = 1;

/// Reads a scene's STEP or IGES object as triangles (scenes::CadMeshReader's signature).
using CadObjectReader = meshio::MeshData (*)(const std::filesystem::path& path, meshio::ReadBudget& budget);

/// What the program gives a module at load.
struct ModuleHost {
  /// The reader of scenes' CAD objects for the module's own scene reads (null: none; the VTK
  /// module gets the program's, which loads the CAD module when a scene names a STEP or IGES part).
  CadObjectReader readCadObject = nullptr;
  /// The program's meshio::vtkPolyDataBytes (it loads the VTK module), for the OpenCASCADE
  /// module's copy of meshio, which links no VTK.
  std::string (*vtkPolyDataBytes)(const meshio::MeshData& mesh, bool xml) = nullptr;
};

/// The VTK module's functions (vtk_module.cpp).
struct VtkModule {
  int (*render)(const Args& args) = nullptr;  ///< ffdkit-cli render, after its options
  int (*plot)(const Args& args) = nullptr;    ///< ffdkit-cli plot
  /// meshio::vtkPolyDataBytes through VTK's writers.
  std::string (*polyDataBytes)(const meshio::MeshData& mesh, bool xml) = nullptr;
};

/// The OpenCASCADE module's functions (cad_module.cpp).
struct CadModule {
  int (*deformCadInput)(const Args& args) = nullptr;        ///< runCadDeform's work (cad_input.h)
  int (*deformSceneCadObject)(const Args& args) = nullptr;  ///< runCadSceneDeform's work
  CadObjectReader readCadObject = nullptr;                   ///< cad_scene::readCadObject, default tessellation
};

/// A module's entry point: checks `version` and `tableSize` (kModuleInterfaceVersion, sizeof its
/// table), then fills `*table`; returns 0, or 1 for a program of another build (nothing filled).
using ModuleEntry = int (*)(int version, std::size_t tableSize, const ModuleHost* host, void* table);

/// The entry points' names and the modules' file names (next to ffdkit-cli in the build tree).
inline constexpr const char* kVtkModuleEntry = "ffdkit_cli_vtk_module";
inline constexpr const char* kCadModuleEntry = "ffdkit_cli_cad_module";
inline constexpr const char* kVtkModuleFile = "ffdkit-cli-vtk.so";
inline constexpr const char* kCadModuleFile = "ffdkit-cli-cad.so";

/// What a module's entry point does: checks the program's `version` and `tableSize` against
/// this build's, then has `fill` fill `*table` for `host`. Returns 0, or 1 (nothing filled).
template <class Table, class Fill>
int fillModuleTable(int version, std::size_t tableSize, const ModuleHost* host, void* table, Fill fill) {
  if (version != kModuleInterfaceVersion || tableSize != sizeof(Table) || host == nullptr || table == nullptr) return 1;
  fill(*host, *static_cast<Table*>(table));
  return 0;
}

}  // namespace ffdkit::cli
