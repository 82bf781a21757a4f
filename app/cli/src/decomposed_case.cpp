#include "decomposed_case.h"

#include <stdexcept>
#include <system_error>

#include "ffdkit/meshio/cell_quality.h"

namespace ffdkit::cli {

namespace fs = std::filesystem;

bool DecomposedCaseInput::applies(const std::vector<std::string>& inputs) {
  return inputs.size() == 1 && meshio::isDecomposedOpenFoamCase(inputs.front());
}

DecomposedCaseInput::DecomposedCaseInput(const fs::path& folder, const ReadSettings& read, const BatchRanks& ranks)
    : case_(meshio::findDecomposedCase(folder)), total_(case_.pieces.size()) {
  const std::size_t size = std::size_t(ranks.size()), rank = std::size_t(ranks.rank());
  meshio::OpenFoamReadOptions options;
  options.limits = read.limits;
  options.confinement = read.confinement;
  for (std::size_t i = rank * total_ / size; i < (rank + 1) * total_ / size; ++i) {
    pieces_.push_back(case_.pieces[i]);
    meshes_.push_back(meshio::readDecomposedCasePiece(case_.pieces[i], options));
  }
}

void DecomposedCaseInput::write(const std::vector<const Eigen::MatrixX3d*>& deformed, const fs::path& output,
                                bool allowInverted, const Console& console, const BatchRanks& ranks) const {
  // Counted over the processor meshes, which hold each cell once (the reconstructed mesh holds
  // them again); a bad cell in any mesh refuses the write.
  std::int64_t bad = 0, cells = 0, badAnywhere = 0;
  std::string badText;
  onEveryRank(ranks, [&] {
    if (deformed.size() != meshes_.size())
      throw std::logic_error("DecomposedCaseInput::write: " + std::to_string(deformed.size()) + " point sets for " +
                             std::to_string(meshes_.size()) + " meshes");
    for (std::size_t i = 0; i < meshes_.size(); ++i) {
      const meshio::CellQuality quality = meshio::checkPolyMeshCells(*deformed[i], meshes_[i].cells);
      badAnywhere += quality.badCells;
      if (!pieces_[i].reconstructed) {
        bad += quality.badCells;
        cells += quality.cellCount;
      }
      if (!quality.ok()) badText += (badText.empty() ? "" : "; ") + pieces_[i].name + ": " + meshio::badCellsText(quality);
    }
  });
  const std::int64_t totalBad = ranks.sum(bad);
  const std::int64_t totalCells = ranks.sum(cells);
  if (ranks.sum(badAnywhere) > 0) {
    const std::string summary = std::to_string(totalBad) + " of the case's " + std::to_string(totalCells) +
                                " cells are inverted or of zero volume";
    if (!allowInverted)
      throw std::runtime_error("the deformed case: " + summary + (badText.empty() ? "" : " (" + badText + ")") +
                               "; nothing written (" + output.string() +
                               " is unchanged; --allow-inverted writes it anyway)");
    if (ranks.leader()) console.warn("writing a case in which " + summary + " (--allow-inverted)");
    if (!badText.empty()) console.warn(badText);  // each process names its own meshes
  }

  std::string staging;
  onEveryRank(ranks, [&] {
    if (ranks.leader()) staging = meshio::stageDecomposedCase(case_, output).string();
  });
  ranks.broadcast(staging);
  try {
    onEveryRank(ranks, [&] {
      for (std::size_t i = 0; i < meshes_.size(); ++i)
        meshio::writeDecomposedCasePiece(pieces_[i], meshes_[i], *deformed[i], staging);
    });
    onEveryRank(ranks, [&] {
      if (ranks.leader()) meshio::commitDecomposedCase(staging, output);
    });
  } catch (...) {
    std::error_code ec;
    if (ranks.leader()) fs::remove_all(staging, ec);  // every rank has stopped writing into it
    throw;
  }
}

}  // namespace ffdkit::cli
