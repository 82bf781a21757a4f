#include "decomposed_case.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <system_error>

#include "ffdkit/meshio/cell_quality.h"

namespace ffdkit::cli {

namespace fs = std::filesystem;

namespace {

meshio::OpenFoamReadOptions readOptionsOf(const ReadSettings& read) {
  meshio::OpenFoamReadOptions options;
  options.limits = read.limits;
  options.confinement = read.confinement;
  return options;
}

/// What the summaries need of one mesh of a decomposed case, read and checked, then let go.
struct PieceFacts {
  std::int64_t points = 0, faces = 0, internalFaces = 0, cells = 0;
  std::string patches;  ///< "inlet (patch, 12 faces), procBoundary0to1 (processor, 30 faces)"
  std::size_t patchCount = 0;
  meshio::CellQuality quality;
};

PieceFacts pieceFacts(const meshio::DecomposedCasePiece& piece, const ReadSettings& read, bool check) {
  const meshio::OpenFoamMesh mesh = meshio::readDecomposedCasePiece(piece, readOptionsOf(read));
  PieceFacts facts;
  facts.points = mesh.points.rows();
  facts.faces = mesh.cells.faceCount();
  facts.internalFaces = std::int64_t(mesh.cells.neighbour.size());
  facts.cells = mesh.cells.cellCount;
  facts.patchCount = mesh.patches.size();
  for (const auto& patch : mesh.patches)
    facts.patches += (facts.patches.empty() ? "" : ", ") + patch.name + " (" + patch.type + ", " +
                     std::to_string(patch.faceCount) + " faces)";
  if (check) facts.quality = meshio::checkPolyMeshCells(mesh.points, mesh.cells);
  return facts;
}

}  // namespace

void infoDecomposedCase(const fs::path& folder, const ReadSettings& read, bool quality) {
  const meshio::DecomposedCase decomposed = meshio::findDecomposedCase(folder);
  const bool reconstructed = decomposed.pieces.size() > decomposed.processorCount;
  std::printf("decomposed OpenFOAM case: %s\n%zu processors%s\n", folder.string().c_str(), decomposed.processorCount,
              reconstructed ? ", and the reconstructed mesh in constant/polyMesh" : "");
  std::int64_t points = 0, cells = 0, bad = 0;
  double minVolume = 0.0, maxVolume = 0.0, totalVolume = 0.0;
  bool first = true;
  for (const auto& piece : decomposed.pieces) {
    const PieceFacts f = pieceFacts(piece, read, quality);
    std::printf("%s: %lld points, %lld faces (%lld internal), %lld cells, %zu patches: %s\n", piece.name.c_str(),
                static_cast<long long>(f.points), static_cast<long long>(f.faces), static_cast<long long>(f.internalFaces),
                static_cast<long long>(f.cells), f.patchCount, f.patches.c_str());
    if (quality) {
      std::printf("  quality: %s\n", meshio::cellQualityText(f.quality).c_str());
      if (!f.quality.ok()) std::printf("  bad cells: %s\n", meshio::badCellsText(f.quality).c_str());
    }
    if (piece.reconstructed) continue;  // its cells are the processors' again
    points += f.points;
    cells += f.cells;
    if (!quality) continue;
    bad += f.quality.badCells;
    totalVolume += f.quality.totalVolume;
    minVolume = first ? f.quality.minVolume : std::min(minVolume, f.quality.minVolume);
    maxVolume = first ? f.quality.maxVolume : std::max(maxVolume, f.quality.maxVolume);
    first = false;
  }
  std::printf("total over the processors: %lld cells, %lld points (a point on a processor boundary counted once per "
              "processor)\n",
              static_cast<long long>(cells), static_cast<long long>(points));
  if (quality)
    std::printf("total quality: volume min %.6g max %.6g sum %.6g, %lld cells inverted or of zero volume\n", minVolume,
                maxVolume, totalVolume, static_cast<long long>(bad));
}

std::string checkDecomposedCase(const fs::path& folder, const ReadSettings& read) {
  const meshio::DecomposedCase decomposed = meshio::findDecomposedCase(folder);
  std::int64_t points = 0, cells = 0;
  std::string badText;
  for (const auto& piece : decomposed.pieces) {
    const PieceFacts f = pieceFacts(piece, read, true);
    if (!f.quality.ok()) badText += (badText.empty() ? "" : "; ") + piece.name + ": " + meshio::badCellsText(f.quality);
    if (piece.reconstructed) continue;
    points += f.points;
    cells += f.cells;
  }
  if (!badText.empty()) throw std::runtime_error(folder.string() + ": " + badText);
  return "decomposed OpenFOAM case, " + std::to_string(decomposed.processorCount) + " processors, " +
         std::to_string(cells) + " cells, " + std::to_string(points) + " points over the processors, all cells valid";
}

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
