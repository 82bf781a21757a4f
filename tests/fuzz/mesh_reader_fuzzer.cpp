// Fuzz target: one mesh reader (FFDKIT_FUZZ_FORMAT, a meshio::MeshFormat) on arbitrary bytes.
// Errors are MeshIoError; anything else (a crash, a sanitizer report, another exception, a
// result that fails validateMesh) is a finding.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "ffdkit/meshio/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ffdkit::meshio;
  try {
    const MeshData mesh = readMeshBytes(std::string_view(reinterpret_cast<const char*>(data), size), MeshFormat::FFDKIT_FUZZ_FORMAT, "fuzz");
    validateMesh(mesh, "fuzz");  // a reader's result must always be valid
  } catch (const MeshIoError&) {
  }
  return 0;
}
