#include "ffdkit/scenes/cad_objects.h"

#include <algorithm>
#include <cctype>
#include <mutex>
#include <string>
#include <utility>

namespace ffdkit::scenes {
namespace {

std::mutex& readerMutex() {
  static std::mutex mutex;
  return mutex;
}

CadMeshReader& registeredReader() {
  static CadMeshReader reader;
  return reader;
}

}  // namespace

bool isCadFile(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".step" || ext == ".stp" || ext == ".iges" || ext == ".igs";
}

void setCadMeshReader(CadMeshReader reader) {
  const std::lock_guard lock(readerMutex());
  registeredReader() = std::move(reader);
}

bool hasCadMeshReader() {
  const std::lock_guard lock(readerMutex());
  return static_cast<bool>(registeredReader());
}

MeshData readCadMesh(const std::filesystem::path& path, meshio::ReadBudget& budget) {
  CadMeshReader reader;
  {
    const std::lock_guard lock(readerMutex());
    reader = registeredReader();
  }
  if (!reader)
    throw MeshIoError(path.string() + ": a STEP or IGES part; this program reads none (the app built with "
                                      "OpenCASCADE, FFDKIT_WITH_CAD, reads them as objects; ffdkit-cli deform "
                                      "takes them as its INPUT)");
  return reader(path, budget);
}

}  // namespace ffdkit::scenes
