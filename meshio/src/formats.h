#pragma once
// The readers and writers of each format, from and to bytes in memory. Private to meshio;
// mesh_io.cpp picks one by MeshFormat. Every reader charges what it allocates for the file to
// `budget` first (ReadBudget::chargePoints for points, chargeBytes for cells and decoded data);
// a ReadLimitError or std::bad_alloc it lets through becomes a MeshIoError in mesh_io.cpp.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "ffdkit/meshio/atomic_write.h"
#include "ffdkit/meshio/mesh_io.h"

namespace ffdkit::meshio::detail {

/// Reads the regular file `path` whole with read(2) into the buffer `allocate(size)` returns
/// (the caller's: an uninitialised array, a string); returns the size.
/// @throws MeshIoError naming the file when it cannot be opened, is not a regular file, or
///   cannot be read to its end.
std::size_t readRegularFile(const std::filesystem::path& path, const std::function<char*(std::size_t)>& allocate);

MeshData readPly(std::string_view bytes, const std::string& source, ReadBudget& budget);
void writePly(ByteSink& out, const MeshData& mesh, PlyEncoding encoding);
/// Records of a binary PLY as writePly writes them (`normals` may be null):
/// the vertex element, and the face and edge elements after it. Their sizes in bytes: a vertex
/// (float x, y, z; with normals twice that), a triangle (uchar 3, three int), an edge (two int).
constexpr std::size_t kPlyVertexBytes = 12, kPlyTriangleBytes = 13, kPlyEdgeBytes = 8;
class BinaryChunks;
void writePlyVertices(BinaryChunks& chunks, const Eigen::MatrixX3d& points, const Eigen::MatrixX3d* normals, bool big);
void writePlyCells(BinaryChunks& chunks, const Eigen::MatrixX3i& triangles, const Eigen::MatrixX2i& segments, bool big);
/// The header writePly writes for these counts.
std::string plyHeader(Eigen::Index vertices, bool normals, Eigen::Index triangles, Eigen::Index segments, PlyEncoding encoding);

/// A binary PLY read in slices of its vertices (vertex_slices.h): the header parsed from the
/// file's first bytes and its counts checked against the file's size, as readPly does. The
/// vertex element must hold the first data (elements before it empty) and have scalar
/// properties only, so that vertex i is the fixed-size record at vertexOffset() + i * recordBytes().
class PlySlices {
 public:
  /// `prefix`: the file's first bytes, at least its header (readPly reads at most 1 MiB of
  /// header). @throws MeshIoError naming the file: a malformed header, counts the file cannot
  /// hold, or a layout without fixed-size vertex records (ASCII, a list property).
  PlySlices(std::string_view prefix, std::uint64_t fileBytes, const std::string& source);
  ~PlySlices();

  long long vertexCount() const { return vertexCount_; }
  std::uint64_t vertexOffset() const { return vertexOffset_; }
  std::uint64_t recordBytes() const { return recordBytes_; }
  std::uint64_t cellsOffset() const { return cellsOffset_; }  ///< just after the last vertex record
  bool hasCells() const { return hasCells_; }                 ///< elements with items after the vertices
  long long faceCount() const { return faceCount_; }
  bool hasNormals() const;

  /// The records of vertices [first, first + points.rows()) into `points`, checked as readPly
  /// checks them (a failure names the vertex by its index in the file).
  void decode(std::string_view records, long long first, Eigen::MatrixX3d& points) const;
  /// The elements after the vertices (`tail`: the bytes from cellsOffset() to the file's end):
  /// faces and edges checked against the vertex count, as readPly reads them; points left empty.
  MeshData readCells(std::string_view tail, ReadBudget& budget) const;

 private:
  struct Layout;
  std::unique_ptr<Layout> layout_;
  std::string source_;
  long long vertexCount_ = 0;
  std::uint64_t vertexOffset_ = 0, recordBytes_ = 0, cellsOffset_ = 0;
  bool hasCells_ = false;
  long long faceCount_ = 0;
};

MeshData readObj(std::string_view bytes, const std::string& source, ReadBudget& budget);
void writeObj(ByteSink& out, const MeshData& mesh);

MeshData readStl(std::string_view bytes, const std::string& source, ReadBudget& budget);
void writeStl(ByteSink& out, const MeshData& mesh);
/// A binary STL triangle as writeStl writes it: normal and three corners (12 floats), attribute word.
constexpr std::size_t kStlTriangleBytes = 50;

MeshData readXyz(std::string_view bytes, const std::string& source, ReadBudget& budget);
void writeXyz(ByteSink& out, const MeshData& mesh);
/// The points of writeXyz (a line each), for a slice of a file.
void writeXyzPoints(ByteSink& out, const Eigen::MatrixX3d& points);
/// The points of .xyz text that starts at line `firstLine` of the file, after `firstPoint` points
/// (the numbers messages give); no points is not an error here.
Eigen::MatrixX3d readXyzPoints(std::string_view bytes, const std::string& source, int firstLine, long long firstPoint,
                               ReadBudget& budget);
/// Newlines and point lines (neither blank nor a comment) of .xyz text, without parsing.
struct XyzCounts {
  long long lines = 0;
  long long points = 0;
};
XyzCounts countXyz(std::string_view bytes);

MeshData readNpy(std::string_view bytes, const std::string& source, ReadBudget& budget);
void writeNpy(ByteSink& out, const MeshData& mesh);
/// The data records writeNpy writes after its header: three little-endian doubles a point.
constexpr std::size_t kNpyRecordBytes = 24;
void writeNpyRecords(BinaryChunks& chunks, const Eigen::MatrixX3d& points);
/// The header writeNpy writes for `rows` points.
std::string npyHeader(Eigen::Index rows);
/// Where an .npy file's data are and how they are laid out, from its header.
struct NpyLayout {
  std::size_t dataOffset = 0;
  long long rows = 0;
  std::size_t itemSize = 8;
  bool bigEndian = false;
  bool fortranOrder = false;
};
/// Parses and checks the header in `prefix` (the file's first bytes); the data must fill the
/// rest of the `fileBytes` exactly. @throws MeshIoError as readNpy.
NpyLayout readNpyHeader(std::string_view prefix, std::uint64_t fileBytes, const std::string& source);
/// Rows [first, first + points.rows()) of a C-order array from their bytes, checked finite
/// (a failure names the point by its index in the file).
void decodeNpyRows(const NpyLayout& layout, std::string_view bytes, long long first, Eigen::MatrixX3d& points,
                   const std::string& source);

/// `folder`: the folder of the glTF file, against which every URI it names is resolved and
/// confined (confinedPath with `confinement`); nullopt (a stream): no external file is read.
MeshData readGltf(std::string_view bytes, bool binary, const std::string& source,
                  const std::optional<std::filesystem::path>& folder, const PathConfinement& confinement, ReadBudget& budget);

MeshData readLegacyVtk(std::string_view bytes, const std::string& source, ReadBudget& budget);
MeshData readVtp(std::string_view bytes, const std::string& source, ReadBudget& budget);

/// The largest magnitude a double may have and still round to a finite float32 (FLT_MAX plus
/// half its last place: 2^128 - 2^103; a tie rounds to even, which is infinity).
constexpr double kFloat32RoundingLimit = 340282356779733661637539395458142568448.0;
/// Checks that every coordinate of `points` rounds to a finite float32, before a writer that
/// stores float32 writes anything. `firstIndex`: the index of row 0 in the whole mesh (a slice).
/// @throws MeshIoError "vertex 17 (x) = 1e+39 does not fit the float32 coordinates of binary PLY".
void requireFloat32Points(const Eigen::MatrixX3d& points, std::string_view formatName, long long firstIndex = 0);

}  // namespace ffdkit::meshio::detail
