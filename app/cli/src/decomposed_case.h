#pragma once
// A decomposed OpenFOAM case given to deform (docs/volume-meshes.md, docs/scaling.md): its meshes
// (the processor folders, and the reconstructed mesh while the case still has it;
// meshio/openfoam_decomposed.h) shared out among the processes of an mpirun batch, or all held by
// one process. Each process reads, deforms and checks its meshes; the case is written only when
// no process found an inverted cell (or with --allow-inverted), all or nothing: every process
// writes its meshes into one hidden copy beside OUTPUT, which rank 0 renames into place once all
// have finished. Deforming moves each point on its own, so the processor meshes come out as
// decomposing the deformed reconstructed case would make them.

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "batch_ranks.h"
#include "console.h"
#include "ffdkit/meshio/openfoam_decomposed.h"
#include "read_options.h"

namespace ffdkit::cli {

/// `info` of a decomposed case: for each of its meshes (the reconstructed one when the case still
/// has it, then each processor) its points, faces, cells and patches, and with `quality` its cell
/// check; then the totals over the processor meshes, which hold each cell of the case once. The
/// meshes are read one at a time. @throws meshio::MeshIoError naming the file.
void infoDecomposedCase(const std::filesystem::path& folder, const ReadSettings& read, bool quality);

/// `validate` of a decomposed case: reads every mesh and checks its cells. Returns the summary
/// line (processors, cells, points). @throws std::runtime_error naming each mesh with bad cells
/// and its first cells; meshio::MeshIoError naming a file that cannot be read.
std::string checkDecomposedCase(const std::filesystem::path& folder, const ReadSettings& read);

/// A decomposed OpenFOAM case given as deform's INPUT.
class DecomposedCaseInput {
 public:
  /// Whether `inputs` is one decomposed case (a folder with processor* folders).
  static bool applies(const std::vector<std::string>& inputs);

  /// Finds the case's meshes and reads this rank's share: a contiguous run of the list
  /// (reconstructed mesh first, then processor0, processor1, ...), [r P / N, (r+1) P / N) for
  /// rank r of N and P meshes; a rank may have none. Not collective.
  /// @throws meshio::MeshIoError naming the file.
  DecomposedCaseInput(const std::filesystem::path& folder, const ReadSettings& read, const BatchRanks& ranks);

  /// This rank's meshes, in order.
  std::size_t ownCount() const { return meshes_.size(); }
  /// The name of this rank's mesh `i` ("processor3", "case").
  const std::string& name(std::size_t i) const { return pieces_[i].name; }
  /// The points of this rank's mesh `i` (#P x 3), moved out: call once.
  Eigen::MatrixX3d takePoints(std::size_t i) { return std::move(meshes_[i].points); }
  /// All meshes of the case, on every rank.
  std::size_t totalCount() const { return total_; }

  /// Checks the cells of each of this rank's meshes with its deformed points (`deformed[i]`, #P x
  /// 3, in the order of name(i)), then writes the case to `output` when no rank found a bad cell,
  /// or when `allowInverted` (and says how many). Collective.
  /// @throws std::runtime_error on every rank when a rank found bad cells (those ranks name the
  /// meshes and cells) and !allowInverted, meshio::MeshIoError when a write fails; `output` is
  /// then as it was and no temporary is left.
  void write(const std::vector<const Eigen::MatrixX3d*>& deformed, const std::filesystem::path& output,
             bool allowInverted, const Console& console, const BatchRanks& ranks) const;

 private:
  meshio::DecomposedCase case_;
  std::vector<meshio::DecomposedCasePiece> pieces_;  ///< this rank's share
  std::vector<meshio::OpenFoamMesh> meshes_;         ///< read, one per piece
  std::size_t total_ = 0;
};

}  // namespace ffdkit::cli
