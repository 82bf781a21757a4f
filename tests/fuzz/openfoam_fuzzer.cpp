// Fuzz target: the OpenFOAM polyMesh file parsers (meshio/openfoam.h) on arbitrary bytes. The
// first byte picks the file: 0 points, 1 faces, 2 a label list (owner, neighbour), 3 boundary;
// the rest is the file. Errors are MeshIoError; anything else (a crash, a sanitizer report,
// another exception) is a finding, and so is a points file that does not come back byte for
// byte from the pass-through writer, or whose written values do not read back.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "ffdkit/meshio/openfoam.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ffdkit::meshio;
  if (size == 0) return 0;
  const std::string_view bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  ReadLimits limits;
  limits.maxMemoryBytes = std::uint64_t(64) << 20;  // an input may ask for no more than this
  limits.maxPoints = 1'000'000;
  ReadBudget budget(limits);
  try {
    switch (data[0] % 4) {
      case 0: {
        FoamPointsFile file;
        const Eigen::MatrixX3d points = readFoamPoints(bytes, "points", budget, &file);
        file.bytes = std::string(bytes);
        if (foamPointsBytes(file, points) != bytes) std::abort();  // pass-through of unchanged points
        const Eigen::MatrixX3d moved = points * 0.5;
        // What the file can hold: a float32 binary file rounds each value to float.
        const Eigen::MatrixX3d held = file.layout.binary && file.layout.scalarBytes == 4
                                          ? Eigen::MatrixX3d(moved.cast<float>().cast<double>())
                                          : moved;
        ReadBudget again(limits);
        if (!(readFoamPoints(foamPointsBytes(file, moved), "points", again) == held)) std::abort();
        break;
      }
      case 1: {
        PolyMeshCells cells;
        readFoamFaces(bytes, "faces", 1000, budget, cells);
        for (std::size_t f = 0; f + 1 < cells.faceStarts.size(); ++f)
          if (cells.faceStarts[f + 1] - cells.faceStarts[f] < 3) std::abort();
        for (std::int32_t v : cells.faceVertices)
          if (v < 0 || v >= 1000) std::abort();
        break;
      }
      case 2: {
        for (std::int32_t label : readFoamLabels(bytes, "owner", 5000, budget))
          if (label < 0 || label > 5000) std::abort();
        break;
      }
      default:
        (void)readFoamBoundary(bytes, "boundary", 100, 200);
    }
  } catch (const MeshIoError&) {
  } catch (const ReadLimitError&) {
  }
  return 0;
}
