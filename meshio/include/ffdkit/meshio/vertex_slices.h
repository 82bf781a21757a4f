#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "ffdkit/meshio/atomic_write.h"
#include "ffdkit/meshio/mesh_data.h"
#include "ffdkit/meshio/mesh_format.h"
#include "ffdkit/meshio/read_limits.h"

namespace ffdkit::meshio {

/// One large point or mesh file read by several processes at once, each reading only the bytes
/// of its own slice of the vertices (the ranks of an mpirun batch, docs/scaling.md). Readable in
/// slices: binary PLY whose vertex element holds the first data and has scalar properties only
/// (vertex i is a fixed-size record), C-order .npy (row i is 3 numbers), and .xyz (cut at line
/// starts). Every slice is checked as readMesh checks the whole file (the header's counts
/// against the file's size, finite numbers, face indices in range), and messages name the file
/// and the vertex (xyz: also the line) by its place in the whole file.
class VertexSliceReader {
 public:
  /// Opens `path`; PLY and npy: reads and checks the header against the file's size. What the
  /// slices read through this reader allocate is charged to one budget of `limits`.
  /// @throws MeshIoError naming the file: not readable in slices (another format, ASCII PLY, a
  ///         list vertex property, a Fortran-order array) or a malformed header.
  explicit VertexSliceReader(const std::filesystem::path& path, const ReadLimits& limits = {});
  ~VertexSliceReader();
  VertexSliceReader(const VertexSliceReader&) = delete;
  VertexSliceReader& operator=(const VertexSliceReader&) = delete;

  /// The file's format (from its extension and header).
  MeshFormat format() const;
  /// PLY and npy: the vertex count of the header; xyz: nullopt (known once every part is counted).
  std::optional<std::int64_t> vertexCount() const;
  /// PLY: the file has normals and faces (its writers would recompute the normals of a vertex
  /// from its neighbours, which another slice may hold).
  bool hasNormalsAndFaces() const;

  /// PLY and npy: vertices [first, last) (#last-first x 3), reading only their bytes.
  /// @throws MeshIoError naming the file, the vertex and the fault (truncated, non-finite).
  Eigen::MatrixX3d readVertices(std::int64_t first, std::int64_t last) const;

  /// A part of an .xyz file's text, with its newline and point-line counts.
  struct TextPart {
    std::string text;         ///< the part's bytes
    std::int64_t lines = 0;   ///< newlines in it
    std::int64_t points = 0;  ///< point lines in it
  };
  /// xyz: part `part` of `parts`: from the first line that starts at or after byte
  /// part * size / parts (byte 0 for part 0) to where the next part starts, so that every line
  /// is in exactly one part. Reads the part and, to find its ends, a little after each.
  TextPart readXyzPart(int part, int parts) const;
  /// xyz: the points of a part that follows `linesBefore` lines and `pointsBefore` points of the
  /// file (the exclusive sums over the parts before it: messages number lines and points as for
  /// the whole file). @throws MeshIoError as readMesh.
  Eigen::MatrixX3d parseXyzPart(const TextPart& part, std::int64_t linesBefore, std::int64_t pointsBefore) const;

  /// PLY: the faces and edges, read from the bytes after the vertices and checked against the
  /// vertex count (points empty); npy, xyz: an empty MeshData. The cells are charged as readMesh
  /// charges them, to a budget of the reader's limits that holds every vertex of the file (not
  /// only the slices read here): a split read refuses what a whole read refuses.
  /// @throws MeshIoError naming the file and the limit.
  MeshData readCells() const;

 private:
  Eigen::MatrixX3d readSlice(std::int64_t first, std::int64_t last) const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Writes in slices of vertices what meshFileBytes writes for the whole mesh: for slices
/// P_0..P_{N-1} of its points (in order), head + vertices(P_0) + ... + vertices(P_{N-1}) + tail
/// is byte for byte the file of the whole mesh, so each process can write its slice at its
/// offset. Formats: binary little-endian PLY (no normals: they need every slice), .npy, .xyz.
bool isSliceWritable(MeshFormat format);
/// The bytes before the first vertex (PLY and npy headers; xyz: none) of a file of `vertices`
/// points and `cells`' triangles and segments (PLY).
std::string slicedFileHead(MeshFormat format, std::int64_t vertices, const MeshData& cells);
/// The bytes of `points` (#P x 3) as consecutive vertices of the file.
std::string slicedFileVertices(MeshFormat format, const Eigen::MatrixX3d& points);
/// The same, written to `out` as they are made (PLY, npy: through a 1 MiB buffer).
void writeSlicedVertices(ByteSink& out, MeshFormat format, const Eigen::MatrixX3d& points);
/// How many bytes slicedFileVertices gives for `rows` points: PLY, npy: fixed-size records;
/// xyz: nullopt (text of varying length).
std::optional<std::uint64_t> slicedVerticesSize(MeshFormat format, Eigen::Index rows);
/// The bytes after the last vertex (PLY: the faces and edges of `cells`; npy, xyz: none).
std::string slicedFileTail(MeshFormat format, const MeshData& cells);
/// The same, written to `out` as they are made; slicedTailSize bytes.
void writeSlicedTail(ByteSink& out, MeshFormat format, const MeshData& cells);
std::uint64_t slicedTailSize(MeshFormat format, const MeshData& cells);

}  // namespace ffdkit::meshio
