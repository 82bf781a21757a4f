// Reading and writing one point or mesh file in slices of its vertices (vertex_slices.h): each
// slice's byte range is read with pread, and the format readers' own header checks and decoders
// do the parsing, so a slice is checked exactly as the whole file would be.
#include "ffdkit/meshio/vertex_slices.h"

#include "ffdkit/meshio/read_failures.h"

#include <cerrno>
#include <cstring>
#include <limits>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "formats.h"
#include "parse_support.h"

namespace ffdkit::meshio {

namespace {

/// The header of a PLY or npy file lies in its first bytes (readPly caps it at 1 MiB).
constexpr std::uint64_t kHeaderPrefix = (1u << 20) + 2;

}  // namespace

struct VertexSliceReader::Impl {
  explicit Impl(const ReadLimits& limits) : budget(limits) {}
  std::string source;
  ReadBudget budget;  // what the slices read through this reader allocate
  MeshFormat format = MeshFormat::Xyz;
  int fd = -1;
  std::uint64_t size = 0;
  std::unique_ptr<detail::PlySlices> ply;
  detail::NpyLayout npy;

  /// Bytes [offset, offset + length) of the file (the length checked against its size first).
  std::string read(std::uint64_t offset, std::uint64_t length) const {
    if (offset > size || length > size - offset)
      throw MeshIoError(source + ": cannot read bytes " + std::to_string(offset) + ".." + std::to_string(offset + length) +
                        ", the file has " + std::to_string(size));
    std::string bytes;
    bytes.resize(std::size_t(length));
    ffd::adviseHugePages(bytes.data(), bytes.size());
    std::size_t done = 0;
    while (done < length) {
      const ssize_t n = ::pread(fd, bytes.data() + done, std::size_t(length) - done, off_t(offset + done));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0)
        throw MeshIoError(source + ": cannot read (" + (n < 0 ? std::strerror(errno) : "the file shrank while read") + ")");
      done += std::size_t(n);
    }
    return bytes;
  }

  /// xyz: where part `part` of `parts` starts: just after the first newline at or after byte
  /// part * size / parts - 1 (so a cut that falls on a line start stays there).
  std::uint64_t partStart(int part, int parts) const {
    if (part <= 0) return 0;
    if (part >= parts) return size;
    // floor(size * part / parts) without overflowing: size = q * parts + r.
    const std::uint64_t cut = size / unsigned(parts) * unsigned(part) + size % unsigned(parts) * unsigned(part) / unsigned(parts);
    constexpr std::uint64_t kChunk = 1 << 16;
    for (std::uint64_t at = cut - 1; at < size; at += kChunk) {
      const std::string chunk = read(at, std::min(kChunk, size - at));
      const std::size_t newline = chunk.find('\n');
      if (newline != std::string::npos) return at + newline + 1;
    }
    return size;
  }
};

namespace {

// What a slice reader lets through becomes its documented error, as in readMesh.
template <class Read>
auto readingSlice(const std::string& source, const ReadBudget& budget, Read&& read) {
  return convertReadFailures<MeshIoError>(source, "a slice", budget, std::forward<Read>(read));
}

}  // namespace

VertexSliceReader::VertexSliceReader(const std::filesystem::path& path, const ReadLimits& limits)
    : impl_(std::make_unique<Impl>(limits)) {
  Impl& d = *impl_;
  d.source = path.string();
  const auto format = meshFormatOf(path);
  if (!format || (*format != MeshFormat::Ply && *format != MeshFormat::Npy && *format != MeshFormat::Xyz))
    throw MeshIoError(d.source + ": cannot be read in slices of vertices (binary .ply, .npy or .xyz can)");
  d.format = *format;
  d.fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (d.fd < 0) throw MeshIoError(d.source + ": cannot open (" + std::strerror(errno) + ")");
  struct stat info {};
  if (::fstat(d.fd, &info) != 0 || !S_ISREG(info.st_mode)) throw MeshIoError(d.source + ": not a regular file");
  d.size = std::uint64_t(info.st_size);
  if (d.format == MeshFormat::Xyz) return;
  const std::string prefix = d.read(0, std::min(d.size, kHeaderPrefix));
  if (d.format == MeshFormat::Ply) {
    d.ply = std::make_unique<detail::PlySlices>(prefix, d.size, d.source);
  } else {
    d.npy = detail::readNpyHeader(prefix, d.size, d.source);
    if (d.npy.fortranOrder)
      throw MeshIoError(d.source + ": cannot be read in slices of vertices: a Fortran-order array keeps each coordinate apart");
  }
}

VertexSliceReader::~VertexSliceReader() {
  if (impl_->fd >= 0) ::close(impl_->fd);
}

MeshFormat VertexSliceReader::format() const { return impl_->format; }

std::optional<std::int64_t> VertexSliceReader::vertexCount() const {
  if (impl_->ply) return impl_->ply->vertexCount();
  if (impl_->format == MeshFormat::Npy) return impl_->npy.rows;
  return std::nullopt;
}

bool VertexSliceReader::hasNormalsAndFaces() const {
  return impl_->ply && impl_->ply->hasNormals() && impl_->ply->faceCount() > 0;
}

Eigen::MatrixX3d VertexSliceReader::readVertices(std::int64_t first, std::int64_t last) const {
  const Impl& d = *impl_;
  const auto count = vertexCount();
  if (!count || first < 0 || last < first || last > *count)
    throw std::logic_error(d.source + ": vertex slice " + std::to_string(first) + ".." + std::to_string(last) + " out of range");
  return readingSlice(d.source, d.budget, [&] { return readSlice(first, last); });
}

Eigen::MatrixX3d VertexSliceReader::readSlice(std::int64_t first, std::int64_t last) const {
  Impl& d = *impl_;
  d.budget.chargePoints(std::uint64_t(last - first), "vertices " + std::to_string(first) + ".." + std::to_string(last));
  Eigen::MatrixX3d points(Eigen::Index(last - first), 3);
  ffd::adviseHugePages(points);
  if (d.ply) {
    const std::string bytes = d.read(d.ply->vertexOffset() + std::uint64_t(first) * d.ply->recordBytes(),
                                     std::uint64_t(last - first) * d.ply->recordBytes());
    d.ply->decode(bytes, first, points);
  } else {
    const std::uint64_t row = 3 * d.npy.itemSize;
    const std::string bytes = d.read(d.npy.dataOffset + std::uint64_t(first) * row, std::uint64_t(last - first) * row);
    detail::decodeNpyRows(d.npy, bytes, first, points, d.source);
  }
  return points;
}

VertexSliceReader::TextPart VertexSliceReader::readXyzPart(int part, int parts) const {
  const Impl& d = *impl_;
  if (d.format != MeshFormat::Xyz) throw std::logic_error(d.source + ": not an .xyz file");
  const std::uint64_t start = d.partStart(part, parts), end = std::max(start, d.partStart(part + 1, parts));
  TextPart result;
  // The part's bytes: a failed allocation is a MeshIoError too.
  result.text = readingSlice(d.source, d.budget, [&] { return d.read(start, end - start); });
  const detail::XyzCounts counts = detail::countXyz(result.text);
  result.lines = counts.lines;
  result.points = counts.points;
  return result;
}

Eigen::MatrixX3d VertexSliceReader::parseXyzPart(const TextPart& part, std::int64_t linesBefore, std::int64_t pointsBefore) const {
  if (linesBefore + 1 > std::numeric_limits<int>::max()) throw MeshIoError(impl_->source + ": more lines than ffdkit numbers");
  return readingSlice(impl_->source, impl_->budget, [&] {
    return detail::readXyzPoints(part.text, impl_->source, int(linesBefore + 1), pointsBefore, impl_->budget);
  });
}

MeshData VertexSliceReader::readCells() const {
  const Impl& d = *impl_;
  if (!d.ply || !d.ply->hasCells()) return {};
  // The cells count as in a read of the whole file: against a budget holding every vertex of
  // the file (the ranks of a batch hold them all between them, and the one reading the cells
  // keeps them beside its own slice), so a split read refuses what readMesh refuses.
  ReadBudget whole(d.budget.limits());
  return readingSlice(d.source, whole, [&] {
    whole.chargePoints(std::uint64_t(d.ply->vertexCount()), "element 'vertex' (every slice)");
    const std::string tail = d.read(d.ply->cellsOffset(), d.size - d.ply->cellsOffset());
    return d.ply->readCells(tail, whole);
  });
}

bool isSliceWritable(MeshFormat format) {
  return format == MeshFormat::Ply || format == MeshFormat::Npy || format == MeshFormat::Xyz;
}

namespace {

void requireSliceWritable(MeshFormat format) {
  if (!isSliceWritable(format))
    throw MeshIoError("cannot write '" + std::string(meshFormatExtension(format)) + "' in slices (.ply, .npy, .xyz can)");
}

}  // namespace

// The pieces are the records of the whole-file writers (writePlyVertices and writePlyCells,
// writeNpyRecords, writeXyzPoints), so that they cannot differ from them.
std::string slicedFileHead(MeshFormat format, std::int64_t vertices, const MeshData& cells) {
  requireSliceWritable(format);
  if (format == MeshFormat::Ply)
    return detail::plyHeader(Eigen::Index(vertices), false, cells.triangles.rows(), cells.segments.rows(),
                             PlyEncoding::BinaryLittleEndian);
  if (format == MeshFormat::Npy) return detail::npyHeader(Eigen::Index(vertices));
  return {};
}

std::optional<std::uint64_t> slicedVerticesSize(MeshFormat format, Eigen::Index rows) {
  requireSliceWritable(format);
  if (format == MeshFormat::Ply) return std::uint64_t(rows) * detail::kPlyVertexBytes;
  if (format == MeshFormat::Npy) return std::uint64_t(rows) * detail::kNpyRecordBytes;
  return std::nullopt;
}

void writeSlicedVertices(ByteSink& out, MeshFormat format, const Eigen::MatrixX3d& points) {
  requireSliceWritable(format);
  if (format == MeshFormat::Xyz) return detail::writeXyzPoints(out, points);  // no copy of the slice
  if (format == MeshFormat::Ply) detail::requireFloat32Points(points, "binary PLY (vertices numbered from the slice's first)");
  detail::BinaryChunks chunks(out);
  if (format == MeshFormat::Ply) detail::writePlyVertices(chunks, points, nullptr, false);
  else detail::writeNpyRecords(chunks, points);
  chunks.flush();
}

std::string slicedFileVertices(MeshFormat format, const Eigen::MatrixX3d& points) {
  detail::StringSink bytes;
  if (const auto size = slicedVerticesSize(format, points.rows())) bytes.text.reserve(std::size_t(*size));
  writeSlicedVertices(bytes, format, points);
  return std::move(bytes.text);
}

std::uint64_t slicedTailSize(MeshFormat format, const MeshData& cells) {
  requireSliceWritable(format);
  if (format != MeshFormat::Ply) return 0;
  return std::uint64_t(cells.triangles.rows()) * detail::kPlyTriangleBytes +
         std::uint64_t(cells.segments.rows()) * detail::kPlyEdgeBytes;
}

void writeSlicedTail(ByteSink& out, MeshFormat format, const MeshData& cells) {
  if (slicedTailSize(format, cells) == 0) return;
  detail::BinaryChunks chunks(out);
  detail::writePlyCells(chunks, cells.triangles, cells.segments, false);
  chunks.flush();
}

std::string slicedFileTail(MeshFormat format, const MeshData& cells) {
  detail::StringSink bytes;
  bytes.text.reserve(std::size_t(slicedTailSize(format, cells)));
  writeSlicedTail(bytes, format, cells);
  return std::move(bytes.text);
}

}  // namespace ffdkit::meshio
