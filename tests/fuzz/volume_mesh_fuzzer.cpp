// Fuzz target: one volume-mesh reader (meshio/volume_mesh.h) on arbitrary bytes, the format
// picked by FFDKIT_FUZZ_VOLUME_FORMAT (Gmsh, Su2, Unv, Elmer, LsDyna, Kratos). Errors are
// MeshIoError (or the budget's ReadLimitError); anything else (a crash, a sanitizer report,
// another exception) is a finding, and so is a file that does not come back byte for byte from
// the pass-through writer, a cell check that throws, or moved points that do not read back (as
// they were, for the formats whose writer keeps every digit).
#include <cstdint>
#include <cstdlib>
#include <string>

#include "ffdkit/meshio/mesh_data.h"
#include "ffdkit/meshio/volume_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ffdkit::meshio;
  constexpr VolumeMeshFormat format = VolumeMeshFormat::FFDKIT_FUZZ_VOLUME_FORMAT;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  ReadLimits limits;
  limits.maxMemoryBytes = std::uint64_t(64) << 20;  // an input may ask for no more than this
  limits.maxPoints = 1'000'000;
  std::unique_ptr<VolumeMesh> mesh;
  try {
    ReadBudget budget(limits);
    mesh = readVolumeMeshBytes(bytes, format, "fuzz", budget);
  } catch (const MeshIoError&) {
    return 0;
  } catch (const ReadLimitError&) {
    return 0;
  }
  const Eigen::MatrixX3d points = mesh->points();
  if (mesh->bytesWith(points) != bytes) std::abort();  // pass-through of unchanged points
  (void)mesh->check(points);
  const Eigen::MatrixX3d moved = points * 0.5;
  std::string written;
  try {
    written = mesh->bytesWith(moved);
  } catch (const MeshIoError&) {
    // A fixed-width field (LS-DYNA, UNV) too narrow for the new value's text.
    if (format != VolumeMeshFormat::LsDyna && format != VolumeMeshFormat::Unv) std::abort();
    return 0;
  }
  try {
    ReadBudget budget(limits);
    const auto again = readVolumeMeshBytes(written, format, "fuzz-written", budget);
    if (again->points().rows() != moved.rows()) std::abort();
    const bool exact = format != VolumeMeshFormat::LsDyna && format != VolumeMeshFormat::Unv;
    if (exact && again->points() != moved) std::abort();
  } catch (const MeshIoError&) {
    std::abort();
  }
  return 0;
}
