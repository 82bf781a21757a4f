// ffdkit-cli's modules found next to the program (build tree) or in its install tree's
// lib/ffdkit, loaded with dlopen at first use, their tables checked (modules.h, docs/cli.md).
#include "module_loader.h"

#include <dlfcn.h>

#include "ffdkit/meshio/vtk_writer.h"
#include "ffdkit/scenes/cad_objects.h"

#include <mutex>
#include <system_error>

#ifndef FFDKIT_CLI_MODULE_DIR
#define FFDKIT_CLI_MODULE_DIR "../lib/ffdkit"
#endif
#ifndef FFDKIT_HAS_CAD
#error "FFDKIT_HAS_CAD (0 or 1) comes from app/cli/CMakeLists.txt"
#endif

namespace ffdkit::cli {

namespace {

namespace fs = std::filesystem;

/// The folder of the running program.
fs::path programFolder() {
  std::error_code error;
  const fs::path program = fs::read_symlink("/proc/self/exe", error);
  if (error) throw ModuleLoadError("cannot find ffdkit-cli's own path (/proc/self/exe: " + error.message() + ")");
  return program.parent_path();
}

/// Loads the module `file` (its first candidate that exists) and fills `table` through its entry
/// point `entry`. @throws ModuleLoadError naming the file and `need`.
void loadModule(const std::string& what, const std::string& file, const char* entry, const std::string& need,
                const ModuleHost& host, void* table, std::size_t tableSize) {
  const std::vector<fs::path> candidates = moduleCandidates(file);
  const fs::path* found = nullptr;
  for (const fs::path& candidate : candidates) {
    std::error_code error;
    if (fs::exists(candidate, error)) {
      found = &candidate;
      break;
    }
  }
  const std::string head = "cannot load ffdkit-cli's " + what + " module ";
  const std::string needs = ", which " + need + " needs: ";
  if (found == nullptr) {
    std::string looked;
    for (const fs::path& candidate : candidates) looked += (looked.empty() ? "" : " and ") + candidate.string();
    throw ModuleLoadError(head + file + needs + "no such file (looked for " + looked + ")");
  }
  void* handle = ::dlopen(found->c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* reason = ::dlerror();
    throw ModuleLoadError(head + found->string() + needs + (reason ? reason : "dlopen failed"));
  }
  auto fill = reinterpret_cast<ModuleEntry>(::dlsym(handle, entry));
  if (fill == nullptr) {
    ::dlclose(handle);
    throw ModuleLoadError(head + found->string() + needs + "it has no entry point " + entry);
  }
  if (fill(kModuleInterfaceVersion, tableSize, &host, table) != 0) {
    ::dlclose(handle);
    throw ModuleLoadError(head + found->string() + needs + "it comes from another build of ffdkit-cli");
  }
  // The module stays loaded to the end of the process: its functions are in the table.
}

/// The table of one module, loaded once; a failed load is tried again at the next call (and
/// fails the same way), so every command that needs the module reports it.
template <class Table>
const Table& loadedTable(const std::string& what, const std::string& file, const char* entry, const std::string& need,
                         const ModuleHost& host) {
  static std::mutex mutex;
  static Table table;
  static bool loaded = false;
  const std::lock_guard lock(mutex);
  if (!loaded) {
    Table filled;
    loadModule(what, file, entry, need, host, &filled, sizeof filled);
    table = filled;
    loaded = true;
  }
  return table;
}

}  // namespace

std::vector<fs::path> moduleCandidates(const std::string& file) {
  const fs::path folder = programFolder();
  return {folder / file, (folder / FFDKIT_CLI_MODULE_DIR / file).lexically_normal()};
}

const VtkModule& vtkModule(const std::string& need) {
  ModuleHost host;
  if (cadModuleBuilt()) host.readCadObject = readCadObjectThroughModule;  // scenes with STEP or IGES parts, rendered
  return loadedTable<VtkModule>("VTK", kVtkModuleFile, kVtkModuleEntry, need, host);
}

const CadModule& cadModule(const std::string& need) {
  ModuleHost host;
  host.vtkPolyDataBytes = meshio::vtkPolyDataBytes;  // the program's: loads the VTK module if ever called
  return loadedTable<CadModule>("OpenCASCADE", kCadModuleFile, kCadModuleEntry, need, host);
}

meshio::MeshData readCadObjectThroughModule(const fs::path& path, meshio::ReadBudget& budget) {
  CadObjectReader read = nullptr;
  try {
    read = cadModule("reading the STEP or IGES object " + path.string()).readCadObject;
  } catch (const ModuleLoadError& e) {
    throw meshio::MeshIoError(e.what());
  }
  return read(path, budget);
}

bool cadModuleBuilt() { return FFDKIT_HAS_CAD != 0; }

void installCadMeshReader() {
  if (cadModuleBuilt()) scenes::setCadMeshReader(readCadObjectThroughModule);
}

}  // namespace ffdkit::cli
