#pragma once
// OpenFOAM polyMesh: a case folder (its constant/polyMesh) or a polyMesh folder, read to deform
// its points and check its cells, and written back by pass-through. `points` is read in ASCII or
// binary, plain or gzip-compressed (`points.gz`); `faces`, `owner`, `neighbour` and `boundary`
// are read for the cell check and never rewritten. The written `points` file is the read one
// byte for byte except the coordinate values (FoamFile header, comments, layout kept); every
// other file of the folder is copied unchanged. File layout: OpenFOAM User Guide, sec. 5.1
// ("Mesh description") and sec. 4.2 ("Basic input/output file format").

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/meshio/label_list.h"
#include "ffdkit/meshio/mesh_data.h"
#include "ffdkit/meshio/path_confinement.h"
#include "ffdkit/meshio/read_limits.h"

namespace ffdkit::meshio {

/// The cells of a polyMesh as OpenFOAM describes them, by their faces: face f has the points
/// faceVertices[faceStarts[f] .. faceStarts[f + 1]) in order; its area vector (right-hand rule)
/// points out of cell owner[f]; the first neighbour.size() faces are internal and point into
/// cell neighbour[f], the others are boundary faces. readOpenFoamMesh reads the lists of a binary
/// file in the machine's own layout in place (LabelList::readInPlace: the file stays mapped for as
/// long as a copy of the list lives), the others into memory.
struct PolyMeshCells {
  /// #F + 1 offsets into faceVertices, faceStarts[0] = 0 (32 bits, as OpenFOAM's faceCompactList
  /// of label=32 stores them: a polyMesh holds fewer than 2^31 face points).
  LabelList faceStarts;
  LabelList faceVertices;  ///< point indices, >= 3 per face
  LabelList owner;         ///< #F cell indices
  LabelList neighbour;     ///< #internal faces cell indices
  std::int64_t cellCount = 0;              ///< 1 + the largest cell index in owner and neighbour

  /// Number of faces, #F.
  std::int64_t faceCount() const { return std::int64_t(owner.size()); }
};

/// A boundary patch of the `boundary` file (read to check it against the faces).
struct PolyMeshPatch {
  std::string name;  ///< the patch's name
  std::string type;  ///< its type (patch, wall, symmetry, ...)
  std::int64_t startFace = 0;  ///< its first face
  std::int64_t faceCount = 0;  ///< its number of faces
};

/// How one OpenFOAM file stores its list, from its FoamFile header.
struct FoamFileLayout {
  bool binary = false;     ///< `format binary;`
  bool bigEndian = false;  ///< binary: `arch "MSB;..."`
  int labelBytes = 4;      ///< binary: `arch "...;label=32|64;..."`
  int scalarBytes = 8;     ///< binary: `arch "...;scalar=32|64"`
  std::string className;   ///< `class`: vectorField, faceList, faceCompactList, labelList, ...
};

/// A `points` file as it was read: its (decompressed) bytes and where its list is, so that the
/// writer can give back the same bytes with other coordinate values.
struct FoamPointsFile {
  /// The whole file, decompressed; or, when omittedBytes > 0, the file without its binary list's
  /// items (readOpenFoamMesh keeps a binary file so: the items are the coordinates the writer
  /// replaces, and keeping them would hold the points twice).
  std::string bytes;
  FoamFileLayout layout;  ///< how its list is stored
  std::size_t listBegin = 0;    ///< just after the list's '('
  std::size_t listEnd = 0;      ///< at the list's ')' in `bytes` (listBegin when the items are omitted)
  std::size_t omittedBytes = 0;  ///< the binary items' bytes left out of `bytes` at listBegin (0: none)
  int listLine = 1;             ///< the line of listBegin (ASCII)
  bool gzip = false;            ///< read from points.gz: written compressed too
  std::string fileName;         ///< "points" or "points.gz"
};

/// How a polyMesh is read: the read budget and the rule for symbolic links in the folder.
struct OpenFoamReadOptions {
  ReadLimits limits{};           ///< the read's limits when `budget` is null
  ReadBudget* budget = nullptr;  ///< a budget shared with an enclosing read, or null
  /// A file of the polyMesh that is a symbolic link leading outside the folder given is refused
  /// unless allowOutside.
  PathConfinement confinement{};
  /// Read faces, owner, neighbour and boundary (false: the points only, e.g. to copy them).
  bool readCells = true;
};

/// An OpenFOAM mesh as read: its points, its cells and its points file for the writer.
struct OpenFoamMesh {
  std::filesystem::path root;      ///< the folder given: a case folder or a polyMesh folder
  std::filesystem::path polyMesh;  ///< root/constant/polyMesh, or root itself
  Eigen::MatrixX3d points;         ///< #P x 3
  PolyMeshCells cells;  ///< faces, owner and neighbour
  std::vector<PolyMeshPatch> patches;  ///< the boundary patches
  FoamPointsFile pointsFile;  ///< the points file as read, for the writer
};

/// Whether `folder` holds an OpenFOAM mesh: constant/polyMesh/points[.gz] below it, or
/// points[.gz] and faces[.gz] in it.
bool isOpenFoamMeshFolder(const std::filesystem::path& folder);

/// The polyMesh folder of `folder` (a case or a polyMesh folder). @throws MeshIoError when
/// `folder` holds no polyMesh.
std::filesystem::path openFoamPolyMeshFolder(const std::filesystem::path& folder);

/// Reads the polyMesh of a case folder or of a polyMesh folder. Validates while it parses: list
/// sizes against the bytes left before anything is allocated (and charged to the budget),
/// point indices of faces and cell indices in range, owner sized as faces, finite coordinates,
/// patches inside the boundary faces; a gzip file's decompressed bytes are charged as they come
/// (a compressed file that expands past --max-memory is refused). A decomposed case
/// (processor* folders) is refused.
/// @throws MeshIoError naming the file and the line (ASCII) or the record (binary).
OpenFoamMesh readOpenFoamMesh(const std::filesystem::path& folder, const OpenFoamReadOptions& options = {});

/// The parsers of the single files: what readOpenFoamMesh calls for each. Each charges `budget`
/// before it allocates and lets its ReadLimitError through (readOpenFoamMesh turns it into a
/// MeshIoError naming the folder).
///
/// The list of a `points` file (vectorField) in `bytes` (decompressed). `points`, when not null,
/// receives what the writer needs.  @throws MeshIoError "points:24: point 3: expected ')'...".
Eigen::MatrixX3d readFoamPoints(std::string_view bytes, const std::string& source, ReadBudget& budget,
                                FoamPointsFile* points = nullptr);
/// The faces of a `faces` file (faceList or faceCompactList) into cells.faceStarts and
/// cells.faceVertices, each point index checked against `pointCount`. @throws MeshIoError.
void readFoamFaces(std::string_view bytes, const std::string& source, std::int64_t pointCount, ReadBudget& budget,
                   PolyMeshCells& cells);
/// A labelList (`owner`, `neighbour`): every label in [0, maxLabel]. @throws MeshIoError.
std::vector<std::int32_t> readFoamLabels(std::string_view bytes, const std::string& source, std::int64_t maxLabel,
                                         ReadBudget& budget);
/// The patches of a `boundary` file, checked to lie in [firstBoundaryFace, faceCount).
std::vector<PolyMeshPatch> readFoamBoundary(std::string_view bytes, const std::string& source,
                                            std::int64_t firstBoundaryFace, std::int64_t faceCount);

/// The bytes of `original` with the coordinates of `points` (#P x 3, as many points as it has)
/// in its list: everything else byte for byte as read. ASCII values are written as the shortest
/// text that reads back as the value, and a value that did not change keeps its text; binary
/// values in the file's scalar size and byte order. Uncompressed. @throws MeshIoError for a
/// point count that differs or a value a float32 file cannot hold.
std::string foamPointsBytes(const FoamPointsFile& original, const Eigen::MatrixX3d& points);

/// Options of the OpenFOAM writer.
struct OpenFoamWriteOptions {
  /// Flush the new files to disk before the folder is renamed into place.
  bool durable = true;
  /// Copy the folder's files on every core (OpenMP), the points file written beside them; false:
  /// everything one after another on the calling thread (a write staged beside a cell check that
  /// keeps the cores busy: stageOpenFoamMesh).
  bool everyCore = true;
};

/// An OpenFOAM folder written in full to a hidden folder beside its output (stageOpenFoamMesh) and
/// not yet in place: commit() renames it onto the output (an existing output folder is exchanged
/// with it atomically and then removed). Destroyed uncommitted, the hidden folder is removed, so
/// nothing is written.
class StagedOpenFoamMesh {
 public:
  /// Takes charge of the written hidden folder `temporary`, to be renamed onto `output` (and the
  /// rename flushed to disk when `durable`).
  StagedOpenFoamMesh(std::filesystem::path temporary, std::filesystem::path output, bool durable)
      : temporary_(std::move(temporary)), output_(std::move(output)), durable_(durable) {}
  ~StagedOpenFoamMesh();
  /// Takes `other`'s hidden folder; `other` then has none (and removes nothing).
  StagedOpenFoamMesh(StagedOpenFoamMesh&& other) noexcept;
  StagedOpenFoamMesh& operator=(StagedOpenFoamMesh&&) = delete;
  StagedOpenFoamMesh(const StagedOpenFoamMesh&) = delete;
  StagedOpenFoamMesh& operator=(const StagedOpenFoamMesh&) = delete;

  /// Puts the folder in place. @throws MeshIoError naming the output (the hidden folder is then
  /// removed when this object is).
  void commit();
  /// The hidden folder (empty once committed or moved from).
  const std::filesystem::path& temporary() const { return temporary_; }

 private:
  std::filesystem::path temporary_;
  std::filesystem::path output_;
  bool durable_ = true;
};

/// writeOpenFoamMesh up to the last step: the whole new folder written (and flushed, when durable)
/// to a hidden folder beside `output`, which the result puts in place or removes. The checks of
/// writeOpenFoamMesh (the point count and values, the output's place) come first.
/// @throws MeshIoError as writeOpenFoamMesh (the hidden folder removed).
StagedOpenFoamMesh stageOpenFoamMesh(const OpenFoamMesh& mesh, const Eigen::MatrixX3d& points,
                                     const std::filesystem::path& output, const OpenFoamWriteOptions& options = {});

/// Writes `mesh`'s folder (mesh.root: a whole case or a polyMesh folder) to `output` with
/// `points` as the coordinates: every file copied unchanged but the points file, which is
/// foamPointsBytes (compressed again when it was read from points.gz). All or nothing: the copy
/// is made in a hidden folder beside `output` and renamed onto it (an existing `output` folder is
/// exchanged with it atomically and then removed), so `output` is the old folder or the complete
/// new one. A symbolic link in the folder that leads outside it is refused, as is an `output`
/// inside the folder. @throws MeshIoError naming the file and the step.
void writeOpenFoamMesh(const OpenFoamMesh& mesh, const Eigen::MatrixX3d& points, const std::filesystem::path& output,
                       const OpenFoamWriteOptions& options = {});

/// The bytes of a gzip-compressed file, inflated; every growth of the result is charged to the
/// budget first, so a small file that expands past the limit is refused. @throws MeshIoError.
std::string gunzipBytes(std::string_view compressed, const std::string& source, ReadBudget& budget);
/// `bytes` gzip-compressed (zlib's default level). @throws MeshIoError.
std::string gzipBytes(std::string_view bytes, const std::string& source);

}  // namespace ffdkit::meshio
