// A decomposed OpenFOAM case: finding its pieces, and writing the case all or nothing from pieces
// written by any number of processes into one hidden folder.
#include "ffdkit/meshio/openfoam_decomposed.h"

#include <algorithm>
#include <charconv>
#include <map>

#include "ffdkit/meshio/atomic_write.h"
#include "openfoam_files.h"

namespace ffdkit::meshio {

namespace fs = std::filesystem;

namespace {

// The number N of a folder named processorN, or -1.
long processorNumber(const std::string& name) {
  constexpr std::string_view prefix = "processor";
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return -1;
  long number = -1;
  const char* first = name.data() + prefix.size();
  const char* last = name.data() + name.size();
  const auto result = std::from_chars(first, last, number);
  if (result.ec != std::errc() || result.ptr != last || number < 0 || (*first == '0' && last - first > 1)) return -1;
  return number;
}

bool hasPolyMesh(const fs::path& folder) {
  std::error_code ec;
  const fs::path polyMesh = folder / "constant" / "polyMesh";
  return fs::exists(polyMesh / "points", ec) || fs::exists(polyMesh / "points.gz", ec);
}

}  // namespace

bool isDecomposedOpenFoamCase(const fs::path& folder) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return false;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind("processor", 0) == 0 && it->is_directory(ec)) return true;
  }
  return false;
}

DecomposedCase findDecomposedCase(const fs::path& folder) {
  DecomposedCase decomposed;
  decomposed.root = folder;
  std::map<long, fs::path> processors;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind("processor", 0) != 0 || !it->is_directory(ec)) continue;
    const long number = processorNumber(name);
    if (number < 0)
      throw MeshIoError(it->path().string() + ": not a processor folder ffdkit reads (processor0, processor1, ...; "
                        "the collated layout processorsN/ is not supported: decompose with -fileHandler uncollated)");
    if (!hasPolyMesh(it->path()))
      throw MeshIoError(it->path().string() + ": no constant/polyMesh/points (a processor folder of decomposePar holds "
                        "its mesh there)");
    processors.emplace(number, it->path());
  }
  if (ec) throw MeshIoError(folder.string() + ": cannot list the folder (" + ec.message() + ")");
  if (processors.empty()) throw MeshIoError(folder.string() + ": not a decomposed OpenFOAM case (no processor* folder)");
  long expected = 0;
  for (const auto& [number, path] : processors) {
    if (number != expected)
      throw MeshIoError(folder.string() + ": processor" + std::to_string(expected) + " is missing (found " +
                        path.filename().string() + "; the processor folders must be numbered 0.." +
                        std::to_string(processors.size() - 1) + ")");
    ++expected;
  }
  if (hasPolyMesh(folder))
    decomposed.pieces.push_back({"case", folder / "constant" / "polyMesh", fs::path("constant") / "polyMesh", true});
  for (const auto& [number, path] : processors)
    decomposed.pieces.push_back({path.filename().string(), path, path.filename(), false});
  decomposed.processorCount = processors.size();
  return decomposed;
}

OpenFoamMesh readDecomposedCasePiece(const DecomposedCasePiece& piece, const OpenFoamReadOptions& options) {
  return readOpenFoamMesh(piece.folder, options);
}

fs::path stageDecomposedCase(const DecomposedCase& decomposed, const fs::path& outputGiven,
                             const OpenFoamWriteOptions& options) {
  const fs::path output = outputGiven.filename().empty() ? outputGiven.parent_path() : outputGiven;
  detail::checkFolderOutput(decomposed.root, output);
  // Skipped: the processor folders (each piece copies its own) and the points the pieces rewrite.
  std::vector<fs::path> skipped;
  for (const DecomposedCasePiece& piece : decomposed.pieces) {
    if (!piece.reconstructed) {
      skipped.push_back(piece.folder);
    } else {
      skipped.push_back(piece.folder / "points");
      skipped.push_back(piece.folder / "points.gz");
    }
  }
  const fs::path parent = output.has_parent_path() ? output.parent_path() : fs::path(".");
  const fs::path staging = temporaryPathBeside(output);
  removeStaleTemporaries(output);  // hidden folders of writers that were killed
  std::error_code ec;
  try {
    fs::create_directories(parent);
    fs::create_directory(staging);
    detail::copyFolder(
        decomposed.root, staging, decomposed.root,
        [&](const fs::path& p) { return std::find(skipped.begin(), skipped.end(), p) != skipped.end(); },
        options.durable);
  } catch (const fs::filesystem_error& e) {
    fs::remove_all(staging, ec);
    throw MeshIoError(output.string() + ": cannot write the case (" + e.what() + ")");
  } catch (...) {
    fs::remove_all(staging, ec);
    throw;
  }
  return staging;
}

void writeDecomposedCasePiece(const DecomposedCasePiece& piece, const OpenFoamMesh& mesh, const Eigen::MatrixX3d& points,
                              const fs::path& staging, const OpenFoamWriteOptions& options) {
  try {
    if (!piece.reconstructed) {
      writeOpenFoamMesh(mesh, points, staging / piece.relative, options);
      return;
    }
    const fs::path folder = staging / piece.relative;
    detail::writeFoamPointsFile(folder / mesh.pointsFile.fileName, mesh.pointsFile, points, options.durable);
    if (options.durable) detail::syncPath(folder);
  } catch (const MeshIoError& e) {
    // The staging folder's name means nothing to the user: name the piece of the case.
    throw MeshIoError(piece.folder.string() + ": " + e.what());
  }
}

void commitDecomposedCase(const fs::path& staging, const fs::path& outputGiven, const OpenFoamWriteOptions& options) {
  const fs::path output = outputGiven.filename().empty() ? outputGiven.parent_path() : outputGiven;
  detail::renameFolderIntoPlace(staging, output, options.durable);
}

}  // namespace ffdkit::meshio
