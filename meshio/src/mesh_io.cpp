#include "ffdkit/meshio/mesh_io.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <new>
#include <stdexcept>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <istream>
#include <iterator>
#include <memory>
#include <ostream>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "ffdkit/meshio/atomic_write.h"
#include "ffdkit/meshio/read_failures.h"
#include "ffdkit/meshio/vtk_writer.h"
#include "formats.h"
#include "parse_support.h"

namespace ffdkit::meshio {

namespace {

constexpr std::pair<std::string_view, MeshFormat> kExtensions[] = {
    {".obj", MeshFormat::Obj},   {".ply", MeshFormat::Ply}, {".stl", MeshFormat::Stl},
    {".xyz", MeshFormat::Xyz},   {".npy", MeshFormat::Npy}, {".gltf", MeshFormat::Gltf},
    {".glb", MeshFormat::Glb},   {".vtp", MeshFormat::Vtp}, {".vtk", MeshFormat::Vtk}};

std::string formatList(bool writable) {
  std::string list;
  for (const auto& [ext, format] : kExtensions)
    if (!writable || isWritable(format)) list.append(list.empty() ? "" : " ").append(ext);
  return list;
}

// The whole file in memory: read(2) into one buffer of the file's size, left uninitialised (the
// read fills it) and backed by huge pages where the system allows (ffd::adviseHugePages).
struct FileBytes {
  std::unique_ptr<char[]> data;
  std::size_t size = 0;
  std::string_view view() const { return {data.get(), size}; }
};

FileBytes readFileBytes(const std::filesystem::path& path) {
  FileBytes bytes;
  bytes.size = detail::readRegularFile(path, [&bytes](std::size_t size) {
    bytes.data = std::make_unique_for_overwrite<char[]>(size);
    ffd::adviseHugePages(bytes.data.get(), size);
    return bytes.data.get();
  });
  return bytes;
}

MeshData parseWith(std::string_view bytes, MeshFormat format, const std::string& source,
                   const std::optional<std::filesystem::path>& folder, const MeshReadOptions& options, ReadBudget& budget) {
  switch (format) {
    case MeshFormat::Obj: return detail::readObj(bytes, source, budget);
    case MeshFormat::Ply: return detail::readPly(bytes, source, budget);
    case MeshFormat::Stl: return detail::readStl(bytes, source, budget);
    case MeshFormat::Xyz: return detail::readXyz(bytes, source, budget);
    case MeshFormat::Npy: return detail::readNpy(bytes, source, budget);
    case MeshFormat::Gltf: return detail::readGltf(bytes, false, source, folder, options.confinement, budget);
    case MeshFormat::Glb: return detail::readGltf(bytes, true, source, folder, options.confinement, budget);
    case MeshFormat::Vtp: return detail::readVtp(bytes, source, budget);
    case MeshFormat::Vtk: return detail::readLegacyVtk(bytes, source, budget);
  }
  throw MeshIoError(source + ": unknown format");
}

// The one place where what a reader lets through becomes its documented error: the budget's
// refusal and a failed allocation get the file in front (the budget's message names the element
// or array), and nothing else than a MeshIoError leaves a reader.
MeshData parseMesh(std::string_view bytes, MeshFormat format, const std::string& source,
                   const std::optional<std::filesystem::path>& folder, const MeshReadOptions& options) {
  ReadBudget own(options.limits);
  ReadBudget& budget = options.budget != nullptr ? *options.budget : own;
  try {
    return convertReadFailures<MeshIoError>(source, "", budget,
                                            [&] { return parseWith(bytes, format, source, folder, options, budget); });
  } catch (const PathOutsideFolderError& e) {
    throw MeshIoError(source + ": " + e.what());
  } catch (const std::length_error&) {
    throw MeshIoError(source + ": out of memory while reading (a size beyond what can be allocated)");
  }
}

}  // namespace

namespace detail {

std::size_t readRegularFile(const std::filesystem::path& path, const std::function<char*(std::size_t)>& allocate) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw MeshIoError(path.string() + ": cannot open (" + std::strerror(errno) + ")");
  struct stat info {};
  if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    ::close(fd);
    throw MeshIoError(path.string() + ": not a regular file");
  }
  const std::size_t size = std::size_t(info.st_size);
  char* data = nullptr;
  try {
    data = allocate(size);
  } catch (...) {
    ::close(fd);
    throw;
  }
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::read(fd, data + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ::close(fd);
      throw MeshIoError(path.string() + ": cannot read (" + (n < 0 ? std::strerror(errno) : "the file shrank while read") + ")");
    }
    done += std::size_t(n);
  }
  ::close(fd);
  return size;
}

void requireFloat32Points(const Eigen::MatrixX3d& points, std::string_view formatName, long long firstIndex) {
  // One vectorised test of the whole block; the offending row is looked for only when it fails.
  if (points.size() == 0 || points.cwiseAbs().maxCoeff() < kFloat32RoundingLimit) return;
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    for (int c = 0; c < 3; ++c)
      if (!(std::abs(points(i, c)) < kFloat32RoundingLimit)) {
        std::string value;
        appendNumber(value, points(i, c));
        static constexpr std::string_view kAxes[] = {"x", "y", "z"};
        throw MeshIoError(Where{"vertex", firstIndex + i, kAxes[c]}.text() + " = " + value +
                          " does not fit the float32 coordinates of " + std::string(formatName) +
                          " (its largest magnitude is 3.4028235e+38); write .ply as ASCII, .npy, .obj, .vtp or .vtk");
      }
}

}  // namespace detail

namespace {

// Checks, before anything is written, that `mesh` fits what `format` can hold: binary PLY and
// STL keep float32 coordinates, STL a 32-bit triangle count (indices are int32 in MeshData, as
// PLY and VTK store them).
void requireRepresentable(const MeshData& mesh, MeshFormat format, const MeshWriteOptions& options) {
  if (format == MeshFormat::Ply && options.plyEncoding != PlyEncoding::Ascii)
    detail::requireFloat32Points(mesh.points, "binary PLY");
  if (format == MeshFormat::Stl) {
    if (std::uint64_t(mesh.triangles.rows()) > std::numeric_limits<std::uint32_t>::max())
      throw MeshIoError(std::to_string(mesh.triangles.rows()) + " triangles do not fit the 32-bit triangle count of binary STL");
    detail::requireFloat32Points(mesh.points, "binary STL");
  }
}

}  // namespace

std::optional<MeshFormat> meshFormatOf(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  for (const auto& [e, format] : kExtensions)
    if (e == ext) return format;
  return std::nullopt;
}

std::string_view meshFormatExtension(MeshFormat format) {
  for (const auto& [ext, f] : kExtensions)
    if (f == format) return ext;
  return "";
}

bool isWritable(MeshFormat format) { return format != MeshFormat::Gltf && format != MeshFormat::Glb; }

MeshData readMeshBytes(std::string_view bytes, MeshFormat format, const std::string& sourceName) {
  return readMeshBytes(bytes, format, sourceName, MeshReadOptions{});
}

MeshData readMesh(std::istream& in, MeshFormat format, const std::string& sourceName) {
  return readMesh(in, format, sourceName, MeshReadOptions{});
}

MeshData readMeshBytes(std::string_view bytes, MeshFormat format, const std::string& sourceName,
                       const MeshReadOptions& options) {
  return parseMesh(bytes, format, sourceName, std::nullopt, options);
}

MeshData readMesh(std::istream& in, MeshFormat format, const std::string& sourceName, const MeshReadOptions& options) {
  std::string bytes;
  try {
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  } catch (const std::bad_alloc&) {
    throw MeshIoError(sourceName + ": out of memory while reading the stream");
  }
  if (in.bad()) throw MeshIoError(sourceName + ": cannot read the stream");
  return readMeshBytes(bytes, format, sourceName, options);
}

MeshData readMesh(const std::filesystem::path& path) { return readMesh(path, MeshReadOptions{}); }

MeshData readMesh(const std::filesystem::path& path, const MeshReadOptions& options) {
  const std::string source = path.string();
  const auto format = meshFormatOf(path);
  if (!format)
    throw MeshIoError(source + ": unknown mesh format '" + path.extension().string() + "' (reads " + formatList(false) + ")");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw MeshIoError(source + ": no such file");
  FileBytes bytes;
  try {
    bytes = readFileBytes(path);
  } catch (const std::bad_alloc&) {
    throw MeshIoError(source + ": out of memory while reading the file's bytes");
  }
  return parseMesh(bytes.view(), *format, source, path.parent_path(), options);
}

namespace {

/// The bytes of `mesh` in `format`, in order, into `out`: the binary layouts stream through a
/// small buffer (BinaryChunks), text formats slice by slice; VTK's writers make one block.
void writeMeshBytes(ByteSink& out, const MeshData& mesh, MeshFormat format, const MeshWriteOptions& options) {
  requireRepresentable(mesh, format, options);
  switch (format) {
    case MeshFormat::Ply: return detail::writePly(out, mesh, options.plyEncoding);
    case MeshFormat::Stl: return detail::writeStl(out, mesh);
    case MeshFormat::Npy: return detail::writeNpy(out, mesh);
    case MeshFormat::Obj: return detail::writeObj(out, mesh);
    case MeshFormat::Xyz: return detail::writeXyz(out, mesh);
    case MeshFormat::Vtp: return out.write(vtkPolyDataBytes(mesh, true));
    case MeshFormat::Vtk: return out.write(vtkPolyDataBytes(mesh, false));
    case MeshFormat::Gltf:
    case MeshFormat::Glb: break;
  }
  throw MeshIoError("cannot write format '" + std::string(meshFormatExtension(format)) + "' (writes " + formatList(true) + ")");
}

}  // namespace

std::string meshFileBytes(const MeshData& mesh, MeshFormat format, const MeshWriteOptions& options) {
  detail::StringSink bytes;
  writeMeshBytes(bytes, mesh, format, options);
  return std::move(bytes.text);
}

void writeMesh(std::ostream& out, const MeshData& mesh, MeshFormat format, const MeshWriteOptions& options) {
  validateMesh(mesh, "<stream>");
  const std::string bytes = meshFileBytes(mesh, format, options);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  if (!out) throw MeshIoError("<stream>: cannot write");
}

StagedFile stageMesh(const std::filesystem::path& path, const MeshData& mesh, const MeshWriteOptions& options) {
  const auto format = meshFormatOf(path);
  if (!format || !isWritable(*format))
    throw MeshIoError(path.string() + ": cannot write format '" + path.extension().string() + "' (writes " + formatList(true) + ")");
  validateMesh(mesh, path.string());
  try {
    return StagedFile(path, [&](ByteSink& out) { writeMeshBytes(out, mesh, *format, options); }, options.durable);
  } catch (const MeshIoError& e) {
    throw MeshIoError(path.string() + ": " + e.what());
  } catch (const std::runtime_error& e) {  // the file's own steps, already naming the path
    throw MeshIoError(e.what());
  }
}

void writeMesh(const std::filesystem::path& path, const MeshData& mesh, const MeshWriteOptions& options) {
  StagedFile staged = stageMesh(path, mesh, options);
  try {
    staged.commit();
  } catch (const std::runtime_error& e) {
    throw MeshIoError(e.what());
  }
}

}  // namespace ffdkit::meshio
