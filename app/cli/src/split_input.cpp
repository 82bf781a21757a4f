#include "split_input.h"

#include <climits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "args.h"
#include "ffdkit/meshio/atomic_write.h"
#include "ffdkit/meshio/mesh_format.h"

namespace ffdkit::cli {

namespace fs = std::filesystem;

namespace {

// Charges the file's `points` to a budget of `limits`; over it, a MeshIoError naming the file.
void chargeWholeFile(const fs::path& path, std::int64_t points, const meshio::ReadLimits& limits) {
  try {
    meshio::ReadBudget(limits).chargePoints(static_cast<std::uint64_t>(points), "vertices");
  } catch (const meshio::ReadLimitError& e) {
    throw meshio::MeshIoError(path.string() + ": " + e.what());
  }
}

}  // namespace

SplitInput::SplitInput(const fs::path& path, const meshio::ReadLimits& limits, const BatchRanks& ranks) : path_(path) {
  std::unique_ptr<meshio::VertexSliceReader> reader;
  onEveryRank(ranks, [&] { reader = std::make_unique<meshio::VertexSliceReader>(path, limits); });
  normalsAndFaces_ = reader->hasNormalsAndFaces();
  if (const auto count = reader->vertexCount()) {
    // PLY, npy: fixed-size records, the count from the header (checked against the file's size).
    const std::int64_t n = *count, r = ranks.rank(), size = ranks.size();
    totalPoints_ = n;
    onEveryRank(ranks, [&] {
      chargeWholeFile(path, n, limits);
      points_ = reader->readVertices(r * n / size, (r + 1) * n / size);
      if (ranks.leader()) cells_ = reader->readCells();
    });
    return;
  }
  // xyz: each rank's lines; the line and point numbers of the ranks before it number its own.
  meshio::VertexSliceReader::TextPart part;
  onEveryRank(ranks, [&] { part = reader->readXyzPart(ranks.rank(), ranks.size()); });
  const std::int64_t linesBefore = ranks.sumBefore(part.lines);
  const std::int64_t pointsBefore = ranks.sumBefore(part.points);
  totalPoints_ = ranks.sum(part.points);
  onEveryRank(ranks, [&] {
    if (totalPoints_ == 0) throw meshio::MeshIoError(path.string() + ": the file has no points");
    if (totalPoints_ > INT_MAX) throw meshio::MeshIoError(path.string() + ": more points than ffdkit indexes");
    chargeWholeFile(path, totalPoints_, limits);
    points_ = reader->parseXyzPart(part, linesBefore, pointsBefore);
  });
}

void SplitInput::checkTarget(const fs::path& target) const {
  const auto format = meshio::meshFormatOf(target);
  if (!format || !meshio::isSliceWritable(*format))
    throw UsageError("-o " + target.string() + ": an mpirun batch that splits one INPUT writes .ply, .npy or .xyz");
  if (*format == meshio::MeshFormat::Ply && normalsAndFaces_)
    throw UsageError(path_.string() + ": a mesh with normals cannot be written as PLY in slices (a vertex's normal "
                     "needs its neighbours on other ranks): write .npy or .xyz, or deform it in one process");
}

void SplitInput::write(const fs::path& target, const Eigen::MatrixX3d& deformed, const BatchRanks& ranks) const {
  const meshio::MeshFormat format = *meshio::meshFormatOf(target);
  // PLY and npy slices have a known size and stream into the file at their place; xyz text is
  // made first to know its size.
  const std::optional<std::uint64_t> fixedSize = meshio::slicedVerticesSize(format, deformed.rows());
  std::string head, text;
  std::uint64_t tailSize = 0;
  onEveryRank(ranks, [&] {
    if (!fixedSize) text = meshio::slicedFileVertices(format, deformed);
    if (ranks.leader()) {
      head = meshio::slicedFileHead(format, totalPoints_, cells_);
      tailSize = meshio::slicedTailSize(format, cells_);
    }
  });
  const std::uint64_t sliceSize = fixedSize ? *fixedSize : text.size();
  ranks.broadcast(head);  // the header's length places every slice
  const std::uint64_t offset = head.size() + std::uint64_t(ranks.sumBefore(std::int64_t(sliceSize)));
  const std::uint64_t tailOffset = head.size() + std::uint64_t(ranks.sum(std::int64_t(sliceSize)));

  std::optional<meshio::StagedFile> staged;
  std::string temporary;
  onEveryRank(ranks, [&] {
    if (!ranks.leader()) return;
    staged.emplace(target, head);
    temporary = staged->temporary().string();
  });
  ranks.broadcast(temporary);
  onEveryRank(ranks, [&] {
    const auto check = [&](std::uint64_t written, std::uint64_t planned, const char* part) {
      if (written != planned)
        throw std::logic_error(target.string() + ": the " + part + " took " + std::to_string(written) + " bytes, " +
                               std::to_string(planned) + " were planned");
    };
    check(meshio::writeStagedPart(temporary, target, offset,
                                  [&](meshio::ByteSink& out) {
                                    if (fixedSize) meshio::writeSlicedVertices(out, format, deformed);
                                    else out.write(text);
                                  }),
          sliceSize, "slice of vertices");
    if (ranks.leader() && tailSize > 0)
      check(meshio::writeStagedPart(temporary, target, tailOffset,
                                    [&](meshio::ByteSink& out) { meshio::writeSlicedTail(out, format, cells_); }),
            tailSize, "faces and edges");
  });
  if (ranks.leader()) staged->commit();
}

}  // namespace ffdkit::cli
