// Gmsh MSH 4.1 (Gmsh reference manual, "MSH file format version 4.1"): sections `$Name` ...
// `$EndName`; in a binary file the section headers, $MeshFormat's first line and $PhysicalNames
// are text and the contents of $Entities, $Nodes and $Elements are raw little- or big-endian
// ints (4 bytes), size_t (the header's data-size, 4 or 8 bytes) and doubles.
#include "ffdkit/meshio/gmsh.h"

#include <algorithm>
#include <bit>
#include <climits>
#include <cmath>
#include <cstring>

#include "ffdkit/meshio/atomic_write.h"
#include "ffdkit/meshio/mesh_data.h"
#include "ffdkit/meshio/read_failures.h"
#include "formats.h"
#include "fresh_buffers.h"
#include "parse_support.h"
#include "text_coordinates.h"

namespace ffdkit::meshio {

namespace {

using detail::LineScanner;

struct TypeInfo {
  int type, nodes, dimension;
  CellShape shape;
};
// Gmsh's element types (GmshDefines.h, MSH_*): the first and second order ones, points, lines up
// to order 5, triangles and quadrilaterals up to order 4, order-3 and order-4 tetrahedra, order-3
// and order-4 hexahedra.
constexpr TypeInfo kTypes[] = {
    {1, 2, 1, CellShape::Triangle},      {2, 3, 2, CellShape::Triangle},     {3, 4, 2, CellShape::Quadrilateral},
    {4, 4, 3, CellShape::Tetrahedron},   {5, 8, 3, CellShape::Hexahedron},   {6, 6, 3, CellShape::Prism},
    {7, 5, 3, CellShape::Pyramid},       {8, 3, 1, CellShape::Triangle},     {9, 6, 2, CellShape::Triangle},
    {10, 9, 2, CellShape::Quadrilateral},{11, 10, 3, CellShape::Tetrahedron},{12, 27, 3, CellShape::Hexahedron},
    {13, 18, 3, CellShape::Prism},       {14, 14, 3, CellShape::Pyramid},    {15, 1, 0, CellShape::Triangle},
    {16, 8, 2, CellShape::Quadrilateral},{17, 20, 3, CellShape::Hexahedron}, {18, 15, 3, CellShape::Prism},
    {19, 13, 3, CellShape::Pyramid},     {20, 9, 2, CellShape::Triangle},    {21, 10, 2, CellShape::Triangle},
    {22, 12, 2, CellShape::Triangle},    {23, 15, 2, CellShape::Triangle},   {24, 15, 2, CellShape::Triangle},
    {25, 21, 2, CellShape::Triangle},    {26, 4, 1, CellShape::Triangle},    {27, 5, 1, CellShape::Triangle},
    {28, 6, 1, CellShape::Triangle},     {29, 20, 3, CellShape::Tetrahedron},{30, 35, 3, CellShape::Tetrahedron},
    {31, 56, 3, CellShape::Tetrahedron}, {36, 16, 2, CellShape::Quadrilateral}, {37, 25, 2, CellShape::Quadrilateral},
    {92, 64, 3, CellShape::Hexahedron},  {93, 125, 3, CellShape::Hexahedron},
};

constexpr std::int64_t kMaxCount = std::int64_t(1) << 40;

// The value of type T stored at `at` (unaligned), its bytes reversed when `swap`.
template <class T>
T loadRaw(const char* at, bool swap) {
  char raw[sizeof(T)];
  std::memcpy(raw, at, sizeof(T));
  if (swap) std::reverse(raw, raw + sizeof(T));
  T value;
  std::memcpy(&value, raw, sizeof(T));
  return value;
}

// A size_t of the file (data-size 4 or 8 bytes) at `at`.
inline std::uint64_t loadSize(const char* at, bool swap, int sizeBytes) {
  return sizeBytes == 8 ? loadRaw<std::uint64_t>(at, swap) : loadRaw<std::uint32_t>(at, swap);
}

// Blocks of at least this many nodes or elements are read on every core (OpenMP): each record
// is at a known offset, and a bad one is looked for again in order so that the message names
// the first, as a serial read would.
constexpr std::uint64_t kParallelRecords = 1 << 15;

// Raw values of a binary section, each read checked against the bytes left.
class BinaryReader {
 public:
  BinaryReader(std::string_view text, std::size_t pos, const std::string& source, bool swap, int sizeBytes)
      : text_(text), pos_(pos), source_(source), swap_(swap), sizeBytes_(sizeBytes) {}

  std::size_t pos() const { return pos_; }
  std::size_t bytesLeft() const { return text_.size() - pos_; }
  int sizeBytes() const { return sizeBytes_; }
  void need(std::uint64_t bytes, const std::string& what) const {
    if (bytes > bytesLeft())
      fail("truncated: " + what + " needs " + std::to_string(bytes) + " bytes at byte offset " + std::to_string(pos_) +
           ", the file has " + std::to_string(bytesLeft()) + " left");
  }
  int integer() { return load<std::int32_t>(); }
  std::uint64_t size() { return sizeBytes_ == 8 ? load<std::uint64_t>() : load<std::uint32_t>(); }
  double real() { return load<double>(); }
  void skip(std::size_t n) { pos_ += n; }
  [[noreturn]] void fail(const std::string& message) const { throw MeshIoError(source_ + ": " + message); }
  std::string at() const { return "byte offset " + std::to_string(pos_); }

 private:
  template <class T>
  T load() {
    const T value = loadRaw<T>(text_.data() + pos_, swap_);
    pos_ += sizeof(T);
    return value;
  }
  std::string_view text_;
  std::size_t pos_;
  const std::string& source_;
  bool swap_;
  int sizeBytes_;
};

// Node tag -> row of the points: a dense table when the tags are compact, else sorted pairs.
class NodeIndex {
 public:
  void build(const std::vector<std::int64_t>& tags, std::int64_t minTag, std::int64_t maxTag, ReadBudget& budget,
             const std::string& source) {
    const std::int64_t n = std::int64_t(tags.size());
    if (n == 0) return;
    if (maxTag - minTag < 4 * n + 1024) {
      min_ = minTag;
      budget.chargeBytes(std::uint64_t(maxTag - minTag + 1), sizeof(std::int32_t), "$Nodes: tag table");
      dense_.clear();
      detail::resizeFresh(dense_, std::size_t(maxTag - minTag + 1), std::int32_t(-1));
      for (std::int64_t i = 0; i < n; ++i) {
        std::int32_t& slot = dense_[std::size_t(tags[std::size_t(i)] - minTag)];
        if (slot >= 0) duplicate(source, tags[std::size_t(i)]);
        slot = std::int32_t(i);
      }
      return;
    }
    budget.chargeBytes(std::uint64_t(n), 16, "$Nodes: tag table");
    sorted_.resize(std::size_t(n));
    for (std::int64_t i = 0; i < n; ++i) sorted_[std::size_t(i)] = {tags[std::size_t(i)], std::int32_t(i)};
    std::sort(sorted_.begin(), sorted_.end());
    for (std::size_t i = 1; i < sorted_.size(); ++i)
      if (sorted_[i].first == sorted_[i - 1].first) duplicate(source, sorted_[i].first);
  }
  /// The row of `tag`, or -1.
  std::int32_t find(std::uint64_t tag) const {
    if (!dense_.empty()) {
      if (tag < std::uint64_t(min_) || tag - std::uint64_t(min_) >= dense_.size()) return -1;
      return dense_[std::size_t(tag - std::uint64_t(min_))];
    }
    const auto it = std::lower_bound(sorted_.begin(), sorted_.end(), std::pair<std::int64_t, std::int32_t>(std::int64_t(tag), -1));
    return it != sorted_.end() && std::uint64_t(it->first) == tag ? it->second : -1;
  }

 private:
  [[noreturn]] static void duplicate(const std::string& source, std::int64_t tag) {
    throw MeshIoError(source + ": $Nodes: node tag " + std::to_string(tag) + " appears twice");
  }
  std::int64_t min_ = 0;
  std::vector<std::int32_t> dense_;
  std::vector<std::pair<std::int64_t, std::int32_t>> sorted_;
};

// Resizes `v` to `size` new items of `value`, growing its capacity at least twofold (a file of
// many element blocks does not reallocate at every block).
template <class T>
void growTo(std::vector<T>& v, std::size_t size, T value) {
  if (size > v.capacity()) {
    v.reserve(std::max(size, 2 * v.capacity()));
    // The new memory beyond the items moved in is fresh (fresh_buffers.h).
    ffd::adviseHugePages(v.data(), v.capacity() * sizeof(T));
  }
  v.resize(size, value);
}

class GmshParser {
 public:
  GmshParser(std::string_view text, const std::string& source, ReadBudget& budget, GmshMesh& mesh)
      : text_(text), source_(source), budget_(budget), mesh_(mesh), s_(text, source) {}

  void parse() {
    bool haveFormat = false, haveNodes = false, haveElements = false;
    for (;;) {
      s_.skipBlanks();
      if (s_.atEnd()) break;
      const int line = s_.line();
      const std::string_view header = s_.takeLine();
      if (!haveFormat && (header.empty() || header[0] != '$'))
        s_.failAt(line, "the file must start with $MeshFormat (not a Gmsh MSH file), got '" +
                            std::string(header.substr(0, 40)) + "'");
      if (header.empty() || header[0] != '$')
        s_.failAt(line, "expected a section ($Name), got '" + std::string(header.substr(0, 40)) + "'");
      const std::string name(header.substr(1));
      if (!haveFormat && name != "MeshFormat") s_.failAt(line, "the file must start with $MeshFormat, not $" + name);
      if (name == "MeshFormat") {
        if (haveFormat) s_.failAt(line, "a second $MeshFormat");
        meshFormat();
        haveFormat = true;
      } else if (name == "PhysicalNames") {
        physicalNames();
      } else if (name == "Entities") {
        entities();
      } else if (name == "Nodes") {
        if (haveNodes) s_.failAt(line, "a second $Nodes section");
        nodes();
        haveNodes = true;
      } else if (name == "Elements") {
        if (!haveNodes) s_.failAt(line, "$Elements before $Nodes");
        if (haveElements) s_.failAt(line, "a second $Elements section");
        elements();
        haveElements = true;
      } else {
        skipSection(name, line);
      }
    }
    if (!haveFormat) s_.fail("no $MeshFormat section (not a Gmsh file)");
    if (!haveNodes) s_.fail("no $Nodes section");
    if (!haveElements) s_.fail("no $Elements section");
  }

 private:
  void expectEnd(const std::string& name) {
    s_.skipBlanks();
    const int line = s_.line();
    const std::string_view end = s_.takeLine();
    if (end != "$End" + name)
      s_.failAt(line, "expected $End" + name + ", got '" + std::string(end.substr(0, 40)) + "' (a count in $" + name +
                          " is wrong, or the section is truncated)");
  }

  void skipSection(const std::string& name, int line) {
    // Sections this reader does not interpret are copied as they are; their end is the first
    // line "$EndName" (in a binary file, the first such bytes after a newline).
    const std::string end = "\n$End" + name;
    const std::size_t at = text_.find(end, s_.pos() == 0 ? 0 : s_.pos() - 1);
    if (at == std::string_view::npos) s_.failAt(line, "$" + name + " has no $End" + name);
    s_.moveTo(at + 1);
    expectEnd(name);
  }

  void meshFormat() {
    const std::string_view version = s_.token(false);
    if (version != "4.1")
      s_.fail("$MeshFormat: version '" + std::string(version) +
              "' is not supported (this reader reads MSH 4.1; gmsh -format msh41 writes it)");
    const long long fileType = s_.integer("$MeshFormat: file-type", 0, 1, false);
    const long long dataSize = s_.integer("$MeshFormat: data-size", 4, 8, false);
    if (dataSize != 4 && dataSize != 8) s_.fail("$MeshFormat: data-size " + std::to_string(dataSize) + " is not 4 or 8");
    if (!s_.atLineEnd()) s_.fail("$MeshFormat: unexpected '" + std::string(s_.token(false)) + "' after the data-size");
    (void)s_.takeLine();
    binary_ = fileType == 1;
    sizeBytes_ = int(dataSize);
    mesh_.file.binary = binary_;
    if (binary_) {
      // The integer 1 in the writer's byte order.
      if (s_.bytesLeft() < 4) s_.fail("$MeshFormat: truncated before the binary integer 1");
      std::int32_t one = 0;
      std::memcpy(&one, text_.data() + s_.pos(), 4);
      if (one == 1) swap_ = false;
      else if (one == 0x01000000) swap_ = true;
      else s_.fail("$MeshFormat: the binary integer after the header is " + std::to_string(one) + ", not 1");
      s_.moveTo(s_.pos() + 4);
      mesh_.file.swapped = swap_;
      s_.useByteOffsets();
    }
    expectEnd("MeshFormat");
  }

  void physicalNames() {
    const std::int64_t n = s_.integer("$PhysicalNames: count", 0, std::int64_t(s_.bytesLeft() / 6));
    for (std::int64_t i = 0; i < n; ++i) {
      const std::string what = "$PhysicalNames: name " + std::to_string(i + 1);
      (void)s_.integer(what + " dimension", 0, 3);
      (void)s_.integer(what + " tag", INT_MIN, INT_MAX, false);
      s_.skipBlanks(false);
      const std::string_view rest = s_.takeLine();
      if (rest.size() < 2 || rest.front() != '"' || rest.back() != '"')
        s_.failAt(s_.line() - 1, what + ": expected a quoted name, got '" + std::string(rest.substr(0, 40)) + "'");
    }
    mesh_.physicalNameCount = n;
    expectEnd("PhysicalNames");
  }

  void entities() {
    if (!binary_) {
      const std::int64_t counts[4] = {s_.integer("$Entities: points", 0, kMaxCount), s_.integer("$Entities: curves", 0, kMaxCount),
                                      s_.integer("$Entities: surfaces", 0, kMaxCount), s_.integer("$Entities: volumes", 0, kMaxCount)};
      mesh_.entityCount = counts[0] + counts[1] + counts[2] + counts[3];
      const std::size_t at = text_.find("\n$EndEntities", s_.pos());
      if (at == std::string_view::npos) s_.fail("$Entities has no $EndEntities");
      s_.moveTo(at + 1);
      expectEnd("Entities");
      return;
    }
    BinaryReader b(text_, s_.pos(), source_, swap_, sizeBytes_);
    b.need(4 * std::uint64_t(sizeBytes_), "$Entities: the four counts");
    std::uint64_t counts[4];
    for (auto& c : counts) c = b.size();
    for (int dim = 0; dim < 4; ++dim) {
      if (counts[dim] > b.bytesLeft() / 4)
        b.fail("$Entities: " + std::to_string(counts[dim]) + " entities of dimension " + std::to_string(dim) +
               " cannot fit in the " + std::to_string(b.bytesLeft()) + " bytes left");
      for (std::uint64_t e = 0; e < counts[dim]; ++e) {
        const std::string what = "$Entities: entity " + std::to_string(e + 1) + " of dimension " + std::to_string(dim);
        b.need(4 + 8 * (dim == 0 ? 3 : 6) + std::uint64_t(sizeBytes_), what);
        b.skip(4 + 8 * (dim == 0 ? 3 : 6));
        const std::uint64_t physical = b.size();
        if (physical > b.bytesLeft() / 4) b.fail(what + ": " + std::to_string(physical) + " physical tags do not fit at " + b.at());
        b.skip(4 * physical);
        if (dim > 0) {
          b.need(std::uint64_t(sizeBytes_), what);
          const std::uint64_t bounding = b.size();
          if (bounding > b.bytesLeft() / 4)
            b.fail(what + ": " + std::to_string(bounding) + " bounding entities do not fit at " + b.at());
          b.skip(4 * bounding);
        }
      }
    }
    mesh_.entityCount = std::int64_t(counts[0] + counts[1] + counts[2] + counts[3]);
    s_.moveTo(b.pos());
    expectEnd("Entities");
  }

  // The four size_t of a $Nodes or $Elements header.
  void sectionHeader(const char* name, std::uint64_t (&h)[4]) {
    if (binary_) {
      BinaryReader b(text_, s_.pos(), source_, swap_, sizeBytes_);
      b.need(4 * std::uint64_t(sizeBytes_), std::string(name) + ": header");
      for (auto& v : h) v = b.size();
      s_.moveTo(b.pos());
    } else {
      const char* fields[4] = {"numEntityBlocks", "count", "minTag", "maxTag"};
      for (int k = 0; k < 4; ++k) h[k] = std::uint64_t(s_.integer(std::string(name) + ": " + fields[k], 0, LLONG_MAX));
    }
    if (h[2] > h[3] && h[1] > 0)
      s_.fail(std::string(name) + ": min tag " + std::to_string(h[2]) + " is above max tag " + std::to_string(h[3]));
  }

  void nodes() {
    std::uint64_t h[4];
    sectionHeader("$Nodes", h);
    const std::uint64_t blocks = h[0], count = h[1];
    // At least a tag and three coordinates per node: "1\n0 0 0\n" or 8 + 24 bytes.
    const std::uint64_t least = binary_ ? std::uint64_t(sizeBytes_) + 24 : 8;
    if (count > s_.bytesLeft() / least)
      s_.fail("$Nodes: " + std::to_string(count) + " nodes need at least " + std::to_string(least) +
              " bytes each, the file has " + std::to_string(s_.bytesLeft()) + " left (truncated, or the count is wrong)");
    if (blocks > s_.bytesLeft() / 8 || blocks > count + 1'000'000)
      s_.fail("$Nodes: " + std::to_string(blocks) + " entity blocks cannot fit in the file");
    budget_.chargePoints(count, "$Nodes: " + std::to_string(count) + " nodes");
    budget_.chargeBytes(count, 8 + (binary_ ? 0 : 36), "$Nodes: tags and coordinate positions");
    mesh_.points.resize(Eigen::Index(count), 3);
    detail::adviseHugePages(mesh_.points);
    detail::resizeFresh(mesh_.nodeTags, std::size_t(count));
    if (!binary_) {
      mesh_.file.spanStarts.reserve(3 * count);
      mesh_.file.spanLengths.reserve(3 * count);
    }
    std::uint64_t read = 0;
    for (std::uint64_t block = 0; block < blocks; ++block) {
      const std::string what = "$Nodes: block " + std::to_string(block + 1);
      int dim, parametric;
      std::uint64_t n;
      BinaryReader b(text_, s_.pos(), source_, swap_, sizeBytes_);
      if (binary_) {
        b.need(12 + std::uint64_t(sizeBytes_), what);
        dim = b.integer();
        (void)b.integer();
        parametric = b.integer();
        n = b.size();
      } else {
        dim = int(s_.integer(what + " entityDim", 0, 3));
        (void)s_.integer(what + " entityTag", INT_MIN, INT_MAX, false);
        parametric = int(s_.integer(what + " parametric", 0, 1, false));
        n = std::uint64_t(s_.integer(what + " numNodesInBlock", 0, LLONG_MAX, false));
      }
      if (dim < 0 || dim > 3) b.fail(what + ": entityDim " + std::to_string(dim) + " is not 0..3 (" + b.at() + ")");
      if (parametric != 0 && parametric != 1) b.fail(what + ": parametric " + std::to_string(parametric) + " is not 0 or 1");
      if (n > count - read)
        s_.fail(what + ": " + std::to_string(n) + " nodes, but the header announces " + std::to_string(count) + " in all and " +
                std::to_string(read) + " came before");
      const int stride = 3 + (parametric == 1 ? dim : 0);
      if (binary_) {
        b.need(n * (std::uint64_t(sizeBytes_) + 8 * std::uint64_t(stride)), what + " (" + std::to_string(n) + " nodes)");
        const char* tags = text_.data() + b.pos();
        const char* xyz = tags + n * std::uint64_t(sizeBytes_);
        const std::size_t nodeBytes = 8 * std::size_t(stride);
        const bool swap = swap_;
        const int sizeBytes = sizeBytes_;
        std::int64_t* tagOut = mesh_.nodeTags.data() + read;
        double* x = mesh_.points.col(0).data() + read;
        double* y = mesh_.points.col(1).data() + read;
        double* z = mesh_.points.col(2).data() + read;
#pragma omp parallel for schedule(static) if (n >= kParallelRecords)
        for (std::int64_t i = 0; i < std::int64_t(n); ++i) {
          tagOut[i] = std::int64_t(loadSize(tags + std::size_t(i) * std::size_t(sizeBytes), swap, sizeBytes));
          const char* at = xyz + std::size_t(i) * nodeBytes;
          x[i] = loadRaw<double>(at, swap);
          y[i] = loadRaw<double>(at + 8, swap);
          z[i] = loadRaw<double>(at + 16, swap);
        }
        mesh_.file.blocks.push_back({std::size_t(xyz - text_.data()), std::int64_t(read), std::int64_t(n), stride});
        s_.moveTo(std::size_t(xyz - text_.data()) + std::size_t(n) * nodeBytes);
      } else {
        for (std::uint64_t i = 0; i < n; ++i)
          mesh_.nodeTags[std::size_t(read + i)] = s_.integer(what + " node tag", 1, LLONG_MAX);
        for (std::uint64_t i = 0; i < n; ++i) {
          const std::string_view pointWhat = "$Nodes: node coordinates";
          s_.skipBlanks();
          for (int c = 0; c < stride; ++c) {
            std::size_t start = 0, length = 0;
            const double value = s_.number(pointWhat, c == 0, &start, &length);
            if (c < 3) {
              mesh_.points(Eigen::Index(read + i), c) = value;
              mesh_.file.spanStarts.push_back(start);
              mesh_.file.spanLengths.push_back(std::uint32_t(length));
            }
          }
          if (!s_.atLineEnd()) s_.fail("$Nodes: node " + std::to_string(mesh_.nodeTags[std::size_t(read + i)]) +
                                       ": unexpected '" + std::string(s_.token(false)) + "' after its coordinates");
        }
      }
      read += n;
    }
    if (read != count)
      s_.fail("$Nodes: the blocks hold " + std::to_string(read) + " nodes, the header announces " + std::to_string(count));
    // The tags in the header's range, binary coordinates finite: checked on every core, the
    // first bad node (in file order) named.
    const std::int64_t* tags = mesh_.nodeTags.data();
    const std::uint64_t minTag = h[2], maxTag = h[3];
    auto badTag = [&](std::int64_t i) {
      return tags[i] < 1 || std::uint64_t(tags[i]) < minTag || std::uint64_t(tags[i]) > maxTag;
    };
    const double* x = mesh_.points.col(0).data();
    const double* y = mesh_.points.col(1).data();
    const double* z = mesh_.points.col(2).data();
    const bool binary = binary_;
    auto badPoint = [&](std::int64_t i) {
      return binary && !(std::isfinite(x[i]) && std::isfinite(y[i]) && std::isfinite(z[i]));
    };
    std::int64_t firstBad = std::int64_t(count);
#pragma omp parallel for schedule(static) reduction(min : firstBad) if (count >= kParallelRecords)
    for (std::int64_t i = 0; i < std::int64_t(count); ++i)
      if (i < firstBad && (badTag(i) || badPoint(i))) firstBad = i;
    if (firstBad < std::int64_t(count)) {
      const std::int64_t tag = tags[firstBad];
      if (badTag(firstBad))
        s_.fail("$Nodes: node tag " + std::to_string(tag) + " is outside the header's range " + std::to_string(h[2]) + ".." +
                std::to_string(h[3]));
      s_.fail("$Nodes: node " + std::to_string(tag) + ": non-finite coordinate");
    }
    index_.build(mesh_.nodeTags, std::int64_t(h[2]), std::int64_t(h[3]), budget_, source_);
    expectEnd("Nodes");
  }

  void elements() {
    std::uint64_t h[4];
    sectionHeader("$Elements", h);
    const std::uint64_t blocks = h[0], count = h[1];
    const std::uint64_t least = binary_ ? 2 * std::uint64_t(sizeBytes_) : 4;
    if (count > s_.bytesLeft() / least)
      s_.fail("$Elements: " + std::to_string(count) + " elements need at least " + std::to_string(least) +
              " bytes each, the file has " + std::to_string(s_.bytesLeft()) + " left (truncated, or the count is wrong)");
    if (blocks > s_.bytesLeft() / 8) s_.fail("$Elements: " + std::to_string(blocks) + " entity blocks cannot fit in the file");
    std::uint64_t read = 0;
    std::int32_t corners[8];
    std::vector<std::int32_t> rows(125);
    for (std::uint64_t block = 0; block < blocks; ++block) {
      const std::string what = "$Elements: block " + std::to_string(block + 1);
      int dim, type;
      std::uint64_t n;
      BinaryReader b(text_, s_.pos(), source_, swap_, sizeBytes_);
      if (binary_) {
        b.need(12 + std::uint64_t(sizeBytes_), what);
        dim = b.integer();
        (void)b.integer();
        type = b.integer();
        n = b.size();
      } else {
        dim = int(s_.integer(what + " entityDim", 0, 3));
        (void)s_.integer(what + " entityTag", INT_MIN, INT_MAX, false);
        type = int(s_.integer(what + " elementType", 1, INT_MAX, false));
        n = std::uint64_t(s_.integer(what + " numElementsInBlock", 0, LLONG_MAX, false));
      }
      int nodes = 0, typeDim = 0;
      CellShape shape{};
      if (!gmshElementType(type, nodes, typeDim, shape))
        s_.fail(what + ": element type " + std::to_string(type) + " is not one this reader knows");
      if (typeDim != dim)
        s_.fail(what + ": element type " + std::to_string(type) + " has dimension " + std::to_string(typeDim) +
                ", its entity " + std::to_string(dim));
      if (n > count - read)
        s_.fail(what + ": " + std::to_string(n) + " elements, but the header announces " + std::to_string(count) +
                " in all and " + std::to_string(read) + " came before");
      if (binary_) b.need(n * std::uint64_t(sizeBytes_) * std::uint64_t(1 + nodes), what + " (" + std::to_string(n) + " elements)");
      if (dim == 3) {
        budget_.chargeBytes(n, 1 + 8 + 8 + 4 * std::uint64_t(cornerCount(shape)), what + ": cells");
        ElementCells& cells = mesh_.cells;
        const std::size_t first = cells.shapes.size(), firstCorner = cells.corners.size();
        const std::size_t k = std::size_t(cornerCount(shape));
        if (binary_) {
          growTo(cells.shapes, first + n, shape);
          growTo(cells.cornerStarts, first + n, std::int64_t(0));
          growTo(cells.ids, first + n, std::int64_t(0));
          growTo(cells.corners, firstCorner + n * k, std::int32_t(0));
          // The hot path of a large binary file: the cells written in place, on every core.
          const char* records = text_.data() + b.pos();
          const std::size_t recordBytes = std::size_t(sizeBytes_) * std::size_t(1 + nodes);
          const bool swap = swap_;
          const int sizeBytes = sizeBytes_;
          std::int64_t firstBad = std::int64_t(n);
#pragma omp parallel for schedule(static) reduction(min : firstBad) if (n >= kParallelRecords)
          for (std::int64_t e = 0; e < std::int64_t(n); ++e) {
            const char* record = records + std::size_t(e) * recordBytes;
            const std::size_t c = first + std::size_t(e);
            cells.ids[c] = std::int64_t(loadSize(record, swap, sizeBytes));
            cells.cornerStarts[c] = std::int64_t(firstCorner + std::size_t(e) * k);
            std::int32_t* corner = cells.corners.data() + firstCorner + std::size_t(e) * k;
            for (int j = 0; j < nodes; ++j) {
              const std::int32_t row = index_.find(loadSize(record + std::size_t(1 + j) * std::size_t(sizeBytes), swap, sizeBytes));
              if (row < 0 && e < firstBad) firstBad = e;
              if (std::size_t(j) < k) corner[j] = row;
            }
          }
          if (firstBad < std::int64_t(n)) {
            const char* record = records + std::size_t(firstBad) * recordBytes;
            for (int j = 0; j < nodes; ++j) {
              const char* at = record + std::size_t(1 + j) * std::size_t(sizeBytes);
              const std::uint64_t node = loadSize(at, swap, sizeBytes);
              if (index_.find(node) < 0)
                b.fail(what + ": element " + std::to_string(loadSize(record, swap, sizeBytes)) + ": node " + std::to_string(node) +
                       " is not in $Nodes (byte offset " + std::to_string(at - text_.data()) + ")");
            }
          }
          s_.moveTo(b.pos() + std::size_t(n) * recordBytes);
          mesh_.elementsByType[type] += std::int64_t(n);
          read += n;
          continue;
        }
        // ASCII: appended cell by cell below (ElementCells::add), the room made once.
        growTo(cells.shapes, first + n, shape);
        growTo(cells.cornerStarts, first + n, std::int64_t(0));
        growTo(cells.ids, first + n, std::int64_t(0));
        growTo(cells.corners, firstCorner + n * k, std::int32_t(0));
        cells.shapes.resize(first);
        cells.cornerStarts.resize(first);
        cells.ids.resize(first);
        cells.corners.resize(firstCorner);
      }
      for (std::uint64_t e = 0; e < n; ++e) {
        const std::int64_t tag = binary_ ? std::int64_t(b.size()) : s_.integer(what + " element tag", 1, LLONG_MAX);
        for (int k = 0; k < nodes; ++k) {
          const std::uint64_t node = binary_ ? b.size() : std::uint64_t(s_.integer(what + " element node", 1, LLONG_MAX, false));
          const std::int32_t row = index_.find(node);
          if (row < 0) {
            const std::string message = what + ": element " + std::to_string(tag) + ": node " + std::to_string(node) +
                                        " is not in $Nodes";
            if (binary_) b.fail(message + " (" + b.at() + ")");
            s_.fail(message);
          }
          rows[std::size_t(k)] = row;
        }
        if (!binary_ && !s_.atLineEnd())
          s_.fail(what + ": element " + std::to_string(tag) + ": more than the " + std::to_string(nodes) + " nodes of type " +
                  std::to_string(type));
        if (dim == 3) {
          std::copy_n(rows.begin(), cornerCount(shape), corners);
          mesh_.cells.add(shape, corners, tag);
        }
      }
      if (binary_) s_.moveTo(b.pos());
      mesh_.elementsByType[type] += std::int64_t(n);
      read += n;
    }
    if (read != count)
      s_.fail("$Elements: the blocks hold " + std::to_string(read) + " elements, the header announces " + std::to_string(count));
    mesh_.elementCount = std::int64_t(count);
    expectEnd("Elements");
  }

  std::string_view text_;
  const std::string& source_;
  ReadBudget& budget_;
  GmshMesh& mesh_;
  LineScanner s_;
  bool binary_ = false;
  bool swap_ = false;
  int sizeBytes_ = 8;
  NodeIndex index_;
};

}  // namespace

bool gmshElementType(int type, int& nodes, int& dimension, CellShape& shape) {
  for (const TypeInfo& t : kTypes)
    if (t.type == type) {
      nodes = t.nodes;
      dimension = t.dimension;
      shape = t.shape;
      return true;
    }
  return false;
}

GmshMesh readGmsh(std::string bytes, const std::string& source, ReadBudget& budget) {
  GmshMesh mesh;
  mesh.file.bytes = std::move(bytes);
  GmshParser(mesh.file.bytes, source, budget, mesh).parse();
  return mesh;
}

GmshMesh readGmsh(const std::filesystem::path& path, const ReadLimits& limits) {
  ReadBudget budget(limits);
  const std::string source = path.string();
  return convertReadFailures<MeshIoError>(source, "the Gmsh file", budget, [&] {
    std::string bytes;
    detail::readRegularFile(path, [&](std::size_t size) {
      budget.chargeBytes(size, 1, "the file's bytes");
      detail::resizeFresh(bytes, size);
      return bytes.data();
    });
    return readGmsh(std::move(bytes), source, budget);
  });
}

std::string gmshBytes(const GmshFile& file, const Eigen::MatrixX3d& points, const std::string& source) {
  if (!file.binary) {
    detail::CoordinateSpans spans;
    spans.starts = file.spanStarts;
    spans.lengths = file.spanLengths;
    return detail::replaceCoordinates(file.bytes, spans, points, source);
  }
  std::int64_t count = 0;
  for (const auto& block : file.blocks) count += block.count;
  if (count != points.rows())
    throw MeshIoError(source + ": " + std::to_string(points.rows()) + " points given for a file of " + std::to_string(count));
  if (!points.allFinite()) throw MeshIoError(source + ": a non-finite coordinate");
  std::string out = file.bytes;
  for (const auto& block : file.blocks) {
    char* at = out.data() + block.offset;
    for (std::int64_t i = 0; i < block.count; ++i, at += 8 * std::size_t(block.stride)) {
      for (int c = 0; c < 3; ++c) {
        char raw[8];
        const double value = points(block.first + i, c);
        std::memcpy(raw, &value, 8);
        if (file.swapped) std::reverse(raw, raw + 8);
        std::memcpy(at + 8 * c, raw, 8);
      }
    }
  }
  return out;
}

void writeGmsh(const GmshMesh& mesh, const Eigen::MatrixX3d& points, const std::filesystem::path& path, bool durable) {
  const std::string source = path.string();
  const GmshFile& file = mesh.file;
  try {
    if (!file.binary) {
      writeFileAtomically(path, gmshBytes(file, points, source), durable);
      return;
    }
    std::int64_t count = 0;
    for (const auto& block : file.blocks) count += block.count;
    if (count != points.rows())
      throw MeshIoError(source + ": " + std::to_string(points.rows()) + " points given for a file of " + std::to_string(count));
    if (!points.allFinite()) throw MeshIoError(source + ": a non-finite coordinate");
    // Streamed: the read bytes go to the file as they are, the coordinate blocks through a small
    // buffer with the new values in place (no copy of the whole file in memory).
    StagedFile staged(path, [&](ByteSink& sink) {
      const std::string_view bytes = file.bytes;
      std::size_t copied = 0;
      std::vector<char> buffer;
      for (const auto& block : file.blocks) {
        sink.write(bytes.substr(copied, block.offset - copied));
        const std::size_t nodeBytes = 8 * std::size_t(block.stride);
        const std::int64_t perChunk = std::max<std::int64_t>(1, std::int64_t((std::size_t(1) << 20) / nodeBytes));
        for (std::int64_t first = 0; first < block.count; first += perChunk) {
          const std::int64_t n = std::min(perChunk, block.count - first);
          const char* from = bytes.data() + block.offset + std::size_t(first) * nodeBytes;
          buffer.assign(from, from + std::size_t(n) * nodeBytes);
          for (std::int64_t i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c) {
              char raw[8];
              const double value = points(block.first + first + i, c);
              std::memcpy(raw, &value, 8);
              if (file.swapped) std::reverse(raw, raw + 8);
              std::memcpy(buffer.data() + std::size_t(i) * nodeBytes + 8 * std::size_t(c), raw, 8);
            }
          sink.write({buffer.data(), buffer.size()});
        }
        copied = block.offset + std::size_t(block.count) * nodeBytes;
      }
      sink.write(bytes.substr(copied));
    }, durable);
    staged.commit();
  } catch (const MeshIoError&) {
    throw;
  } catch (const std::exception& e) {
    throw MeshIoError(e.what());
  }
}

}  // namespace ffdkit::meshio
