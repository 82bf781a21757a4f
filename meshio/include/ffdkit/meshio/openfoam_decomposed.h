#pragma once
// A decomposed OpenFOAM case (decomposePar's output): one polyMesh per processor folder,
// `processor0/constant/polyMesh` ... `processorN-1/constant/polyMesh`, beside the case's own
// (reconstructed) `constant/polyMesh` when it is still there. Each of these meshes is a piece:
// read, deformed, checked and written on its own, by whichever process of a batch holds it, and
// the case is written all or nothing: a hidden copy beside the output is filled piece by piece
// and renamed into place once every piece is in it. File layout: OpenFOAM User Guide, sec. 3.4
// ("Running applications in parallel").

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/meshio/openfoam.h"

namespace ffdkit::meshio {

/// One mesh of a decomposed case.
struct DecomposedCasePiece {
  std::string name;              ///< "processor3", or "case" for the reconstructed mesh
  std::filesystem::path folder;  ///< what readOpenFoamMesh reads: root/processor3, or root/constant/polyMesh
  /// Where its written copy goes, relative to the case folder: "processor3", or "constant/polyMesh".
  std::filesystem::path relative;
  bool reconstructed = false;  ///< the case's own constant/polyMesh (only its points file is rewritten)
};

/// The pieces of a decomposed case: the reconstructed mesh first when the case has one, then the
/// processor folders in number order.
struct DecomposedCase {
  std::filesystem::path root;              ///< the case folder
  std::vector<DecomposedCasePiece> pieces;  ///< every mesh to deform
  std::size_t processorCount = 0;           ///< the processor folders among the pieces
};

/// Whether `folder` holds processor* folders with a polyMesh (processor0/constant/polyMesh).
bool isDecomposedOpenFoamCase(const std::filesystem::path& folder);

/// The pieces of the decomposed case `folder`. @throws MeshIoError when the processor folders are
/// not numbered 0..N-1 without a gap, when one has no constant/polyMesh, or for the collated
/// layout (`processors4/`, one folder for all ranks), which ffdkit does not read.
DecomposedCase findDecomposedCase(const std::filesystem::path& folder);

/// Reads one piece (readOpenFoamMesh of piece.folder, whose processor folder does not count as a
/// decomposed case). @throws MeshIoError naming the file.
OpenFoamMesh readDecomposedCasePiece(const DecomposedCasePiece& piece, const OpenFoamReadOptions& options = {});

/// The first step of writing a decomposed case to `output`: checks `output` (not inside the case,
/// a folder when it exists), makes a fresh hidden folder beside it (see temporaryPathBeside) and
/// copies into it every file of the case but the processor folders and the pieces' points files.
/// Returns the hidden folder; the pieces are then written into it (writeDecomposedCasePiece, by any
/// process that sees the same file system) and it is put in place by commitDecomposedCase, or
/// removed (std::filesystem::remove_all) when a piece fails. A symbolic link leading outside the
/// case is refused, as by writeOpenFoamMesh. @throws MeshIoError naming the file and the step
/// (the hidden folder is removed).
std::filesystem::path stageDecomposedCase(const DecomposedCase& decomposed, const std::filesystem::path& output,
                                          const OpenFoamWriteOptions& options = {});

/// Writes the piece `mesh` (read by readDecomposedCasePiece) with `points` (#P x 3) into the
/// hidden folder `staging`: a processor folder is copied whole with its new points
/// (writeOpenFoamMesh), the reconstructed mesh gets its points file (the rest was staged).
/// @throws MeshIoError naming the file and the step.
void writeDecomposedCasePiece(const DecomposedCasePiece& piece, const OpenFoamMesh& mesh, const Eigen::MatrixX3d& points,
                              const std::filesystem::path& staging, const OpenFoamWriteOptions& options = {});

/// Renames the finished `staging` folder onto `output` (an existing `output` folder is exchanged
/// with it atomically and then removed). @throws MeshIoError; `output` is then unchanged.
void commitDecomposedCase(const std::filesystem::path& staging, const std::filesystem::path& output,
                          const OpenFoamWriteOptions& options = {});

}  // namespace ffdkit::meshio
