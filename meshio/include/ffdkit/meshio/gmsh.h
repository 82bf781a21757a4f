#pragma once
// Gmsh's MSH 4.1 format, ASCII and binary (Gmsh reference manual, sec. "MSH file format"), read
// to deform its nodes and check its volume cells, and written back by pass-through: every byte
// of the file but the nodes' x, y, z is written as it was read (physical names, entities,
// element blocks with their entity tags, node tags, parametric coordinates, any other section).
// Every element type Gmsh writes up to order 2, and its order-3 tetrahedra and hexahedra, are
// read; the 3D ones are checked at their corner nodes (element_cells.h).

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/meshio/element_cells.h"
#include "ffdkit/meshio/read_limits.h"

namespace ffdkit::meshio {

/// A .msh file as read: its bytes and where its node coordinates are, for the writer.
struct GmshFile {
  std::string bytes;    ///< the whole file
  bool binary = false;  ///< `$MeshFormat` file-type 1
  bool swapped = false; ///< binary, in the other byte order than this machine's
  /// Binary: the coordinates of nodes first .. first + count - 1 (in file order) start at byte
  /// `offset`, `stride` doubles per node (3, or more with parametric coordinates).
  struct CoordinateBlock {
    std::size_t offset = 0;   ///< byte offset of the first node's x
    std::int64_t first = 0;   ///< index (file order) of the block's first node
    std::int64_t count = 0;   ///< nodes in the block
    int stride = 3;           ///< doubles per node
  };
  std::vector<CoordinateBlock> blocks;  ///< binary
  /// ASCII: byte offset and length of each coordinate's text, 3 per node in file order.
  std::vector<std::uint64_t> spanStarts;
  std::vector<std::uint32_t> spanLengths;  ///< ASCII: the length of each span in spanStarts
};

/// A Gmsh mesh: its nodes, its volume cells and what the file holds.
struct GmshMesh {
  Eigen::MatrixX3d points;             ///< #N x 3, in the order of the $Nodes section
  std::vector<std::int64_t> nodeTags;  ///< #N node tags
  ElementCells cells;                  ///< the 3D elements (corner nodes as rows of points)
  std::map<int, std::int64_t> elementsByType;  ///< Gmsh element type -> count, all dimensions
  std::int64_t elementCount = 0;       ///< all elements, all dimensions
  std::int64_t physicalNameCount = 0;  ///< entries of $PhysicalNames
  std::int64_t entityCount = 0;        ///< points, curves, surfaces and volumes of $Entities
  GmshFile file;                       ///< for the writer
};

/// Reads a MSH 4.1 file from its bytes (`source` names it in messages). Validates while it
/// parses: every count against the bytes left before anything is allocated (and charged to the
/// budget), node tags unique and inside the header's range, element nodes that exist, finite
/// coordinates, known element types, sections closed by their $End line.
/// @throws MeshIoError "box.msh:41: node block 2: ..." (ASCII: the line) or "box.msh: ... at byte
///   offset 1234" (binary); a ReadLimitError from `budget` is let through.
GmshMesh readGmsh(std::string bytes, const std::string& source, ReadBudget& budget);
/// Reads the file `path` (a regular file) against `limits`. @throws MeshIoError naming it.
GmshMesh readGmsh(const std::filesystem::path& path, const ReadLimits& limits = {});

/// The bytes of `file` with `points` (#N x 3, as many as it has) as the node coordinates:
/// binary values as doubles in place, ASCII values as the shortest text that reads back as the
/// value (a value that did not change keeps its text). @throws MeshIoError.
std::string gmshBytes(const GmshFile& file, const Eigen::MatrixX3d& points, const std::string& source = "mesh");

/// Writes gmshBytes(mesh.file, points) to `path` atomically (meshio/atomic_write.h).
/// @throws MeshIoError naming the file.
void writeGmsh(const GmshMesh& mesh, const Eigen::MatrixX3d& points, const std::filesystem::path& path,
               bool durable = true);

/// The number of nodes of a Gmsh element type, its dimension and its corner shape (a 3D type's
/// shape; for other dimensions the shape is unused). Returns false for a type this reader does
/// not know.
bool gmshElementType(int type, int& nodes, int& dimension, CellShape& shape);

}  // namespace ffdkit::meshio
