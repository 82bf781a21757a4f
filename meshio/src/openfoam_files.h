#pragma once
// File steps shared by the OpenFOAM readers and writers (a case folder, a decomposed case): the
// label lists read in place; copying a folder under the confinement rule, writing a new file,
// flushing, and putting a finished hidden folder in place. Private to meshio.

#include <filesystem>
#include <functional>
#include <memory>
#include <string_view>

#include <Eigen/Core>

#include "ffdkit/meshio/openfoam.h"

namespace ffdkit::meshio::detail {

/// readFoamFaces, with the binary lists of the machine's own layout (label=32, its byte order)
/// read where they lie in `bytes`, which `keeper` keeps readable for as long as a copy of the lists
/// lives (LabelList::inPlace), each label checked first as readFoamFaces checks it; other lists,
/// and every list when `keeper` is null, are read into memory. @throws MeshIoError as readFoamFaces.
void readFoamFacesInPlace(std::string_view bytes, const std::string& source, std::int64_t pointCount, ReadBudget& budget,
                          PolyMeshCells& cells, const std::shared_ptr<const void>& keeper);
/// readFoamLabels, read in place as readFoamFacesInPlace reads its lists.
LabelList readFoamLabelsInPlace(std::string_view bytes, const std::string& source, std::int64_t maxLabel, ReadBudget& budget,
                                const std::shared_ptr<const void>& keeper);

/// Refuses `points` for the binary points file `original`: another point count, or (scalar=32) a
/// value a float32 cannot hold. @throws MeshIoError naming the file.
void checkBinaryFoamPoints(const FoamPointsFile& original, const Eigen::MatrixX3d& points);

/// The binary items of points [first, last) as `layout` stores them (scalar size, byte order), at
/// `out`; returns the end of what it wrote (3 (last - first) scalarBytes bytes).
char* storeFoamPoints(const FoamFileLayout& layout, const Eigen::MatrixX3d& points, Eigen::Index first, Eigen::Index last,
                      char* out);

/// Creates the points file `path` (which must not exist) of `original` with `points`: the bytes
/// foamPointsBytes gives (compressed again for a .gz file), a binary file written from the points a
/// run at a time, without the whole file in memory. Flushed to disk when `durable`.
/// @throws MeshIoError naming the file (check first with foamPointsBytes's rules: the count, a
/// float32 file's values). `direct`: a binary file goes to the disk by direct I/O (O_DIRECT, where
/// the file system takes it) from the buffer its points are formatted into, not through the page
/// cache.
void writeFoamPointsFile(const std::filesystem::path& path, const FoamPointsFile& original, const Eigen::MatrixX3d& points,
                         bool durable, bool direct = false);

/// Creates `path` (which must not exist) with `bytes`, flushed to disk when `durable`.
/// @throws MeshIoError naming the path.
void writeNewFile(const std::filesystem::path& path, std::string_view bytes, bool durable);

/// fsync of a file or folder, when it can be opened (a best effort: the data were written).
void syncPath(const std::filesystem::path& path);

/// Starts writing a file's data to disk without waiting (sync_file_range); a later syncPath waits
/// only for what is left. A best effort, as syncPath.
void startWriteback(const std::filesystem::path& path);

/// Copies the file `from` to the new file `to` (with its permissions) by direct I/O (O_DIRECT):
/// the disk takes the bytes from the source's pages in the page cache (mapped a window at a
/// time), with no copy into fresh cache pages, so the CPU does a fraction of a copy's work; the
/// bytes are on the disk when it returns (the file's metadata wait for a flush, syncPath). The
/// file's last partial block goes through the page cache. Returns false, with nothing left at
/// `to`, when `from` cannot be opened as a regular file or the file system takes no direct I/O:
/// copy it otherwise. @throws MeshIoError naming `to` when a write fails (e.g. the disk is full).
bool copyFileDirectly(const std::filesystem::path& from, const std::filesystem::path& to);

/// Copies the folder `from` into `to` (which exists), but the entries `skip` says true for; a
/// symbolic link is copied as the file it leads to, which must be inside `root`. The files are
/// copied on every core, the largest first, and `alongside` (when given: writing a new file into
/// `to`) runs beside them. When `durable`, every file copied and every folder is flushed to disk
/// before it returns (each file's writing to disk is started as soon as it is copied, so the disk
/// works while the next is copied). `everyCore` false: the copies and `alongside` one after
/// another on the calling thread. Files of 4 MiB or more are copied by copyFileDirectly when
/// `durable`.
/// @throws MeshIoError for a link outside `root`, a link to a folder, or what is neither a file
/// nor a folder (before anything is copied); std::filesystem::filesystem_error for a failed copy;
/// what `alongside` throws.
void copyFolder(const std::filesystem::path& from, const std::filesystem::path& to, const std::filesystem::path& root,
                const std::function<bool(const std::filesystem::path&)>& skip, bool durable,
                const std::function<void()>& alongside = {}, bool everyCore = true);

/// Refuses an `output` inside `root` (other than root itself) and an `output` that exists and is
/// not a folder. @throws MeshIoError.
void checkFolderOutput(const std::filesystem::path& root, const std::filesystem::path& output);

/// Renames the finished folder `temporary` onto `output`: a plain rename when `output` does not
/// exist, else an atomic exchange (RENAME_EXCHANGE) after which the old folder is removed, so that
/// `output` is the old folder or the whole new one at every moment. @throws MeshIoError.
void renameFolderIntoPlace(const std::filesystem::path& temporary, const std::filesystem::path& output, bool durable);

}  // namespace ffdkit::meshio::detail
