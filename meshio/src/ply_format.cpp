// Stanford PLY (Turk 1994): an ASCII header declaring elements and their properties, then the
// data in ASCII or binary (either byte order). Reads "vertex" (x y z, optional nx ny nz),
// "face" (a list of vertex indices, fan-triangulated) and "edge" (vertex1 vertex2); other
// elements are checked and skipped. Every declared element and property is accounted for: a
// property named twice in an element, an element named twice, an edge without vertex1 or
// vertex2, a face without its index list, or connectivity ffdkit does not read (tristrips) is an
// error at its header line, never a column left unset or cells silently dropped.
#include <array>
#include <climits>
#include <vector>

#include "formats.h"
#include "parse_support.h"

namespace ffdkit::meshio::detail {
namespace {

enum class Type { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<Type> typeNamed(std::string_view name) {
  static constexpr std::pair<std::string_view, Type> names[] = {
      {"char", Type::Int8},     {"int8", Type::Int8},      {"uchar", Type::UInt8},    {"uint8", Type::UInt8},
      {"short", Type::Int16},   {"int16", Type::Int16},    {"ushort", Type::UInt16},  {"uint16", Type::UInt16},
      {"int", Type::Int32},     {"int32", Type::Int32},    {"uint", Type::UInt32},    {"uint32", Type::UInt32},
      {"float", Type::Float32}, {"float32", Type::Float32}, {"double", Type::Float64}, {"float64", Type::Float64}};
  for (const auto& [n, t] : names)
    if (n == name) return t;
  return std::nullopt;
}

std::size_t sizeOf(Type t) {
  switch (t) {
    case Type::Int8: case Type::UInt8: return 1;
    case Type::Int16: case Type::UInt16: return 2;
    case Type::Int32: case Type::UInt32: case Type::Float32: return 4;
    case Type::Float64: return 8;
  }
  return 0;
}

bool isInteger(Type t) { return t != Type::Float32 && t != Type::Float64; }

// What a property is for: a coordinate slot of the point or normal, the face's or edge's
// vertex indices, or nothing (checked and skipped).
enum class Role { Ignore, X, Y, Z, NX, NY, NZ, FaceIndices, Edge0, Edge1 };

struct Property {
  std::string name;
  Type type = Type::Float32;
  bool isList = false;
  Type countType = Type::UInt8;
  Role role = Role::Ignore;
};

struct Element {
  std::string name;
  long long count = 0;
  std::vector<Property> properties;
  int headerLine = 0;
};

enum class Encoding { Ascii, Little, Big };

struct Header {
  Encoding encoding = Encoding::Ascii;
  std::vector<Element> elements;
  std::size_t dataOffset = 0;
  int dataLine = 0;  ///< the first data line (ASCII)
};

Header readHeader(std::string_view bytes, const std::string& source) {
  // The header is short text; cap it so a file without "end_header" is not scanned for long.
  constexpr std::size_t kMaxHeader = 1 << 20;
  const std::size_t end = bytes.substr(0, kMaxHeader).find("end_header");
  TextCursor text(bytes.substr(0, end == std::string_view::npos ? std::min(bytes.size(), kMaxHeader) : end + 10), source);
  if (text.word() != "ply") text.fail("not a PLY file (it must start with 'ply')");
  text.endLine({"header"});
  Header header;
  bool haveFormat = false;
  for (;;) {
    if (text.atEnd()) text.fail("the header has no 'end_header' line");
    const std::string_view keyword = text.word();
    if (keyword.empty()) {
      text.nextLine();
    } else if (keyword == "comment" || keyword == "obj_info") {
      text.nextLine();
    } else if (keyword == "format") {
      const std::string_view f = text.word();
      if (f == "ascii") header.encoding = Encoding::Ascii;
      else if (f == "binary_little_endian") header.encoding = Encoding::Little;
      else if (f == "binary_big_endian") header.encoding = Encoding::Big;
      else text.fail("unknown format '" + std::string(f) + "' (ascii, binary_little_endian, binary_big_endian)");
      if (text.word() != "1.0") text.fail("format: only PLY version 1.0 is known");
      text.endLine({"format"});
      haveFormat = true;
    } else if (keyword == "element") {
      Element e;
      e.headerLine = text.line();
      e.name = std::string(text.word());
      if (e.name.empty()) text.fail("element: missing name");
      e.count = text.integer({"element count"}, 0, LLONG_MAX);
      text.endLine({"element"});
      header.elements.push_back(std::move(e));
    } else if (keyword == "property") {
      if (header.elements.empty()) text.fail("property before any element");
      Property p;
      std::string_view typeName = text.word();
      if (typeName == "list") {
        p.isList = true;
        const std::string_view countName = text.word();
        const auto countType = typeNamed(countName);
        if (!countType || !isInteger(*countType)) text.fail("list count type '" + std::string(countName) + "' is not an integer type");
        p.countType = *countType;
        typeName = text.word();
      }
      const auto type = typeNamed(typeName);
      if (!type) text.fail("unknown property type '" + std::string(typeName) + "'");
      p.type = *type;
      p.name = std::string(text.word());
      if (p.name.empty()) text.fail("property: missing name");
      text.endLine({"property"});
      header.elements.back().properties.push_back(std::move(p));
    } else if (keyword == "end_header") {
      // The data start right after this line's newline ("\r\n" too).
      text.skipBlanks();
      if (text.atEnd() && end + 10 < bytes.size() && bytes[end + 10] != '\n' && bytes[end + 10] != '\r')
        text.fail("garbage after 'end_header'");
      std::size_t offset = end + 10;
      while (offset < bytes.size() && bytes[offset] == '\r') ++offset;
      if (offset < bytes.size() && bytes[offset] == '\n') ++offset;
      else if (offset < bytes.size()) text.fail("'end_header' must end its line");
      header.dataOffset = offset;
      header.dataLine = text.line() + 1;
      break;
    } else {
      text.fail("unknown header keyword '" + std::string(keyword) + "'");
    }
  }
  if (!haveFormat) text.fail("the header has no 'format' line");
  return header;
}

// Gives every property its role and checks the elements ffdkit reads have what they need:
// each element named once, each property named once in its element, and each role ffdkit
// reads filled (so that no coordinate or index is left to whatever memory held).
void assignRoles(Header& header, const std::string& source, bool& hasNormals) {
  auto fail = [&](const Element& e, const std::string& message) {
    throw MeshIoError(source + ":" + std::to_string(e.headerLine) + ": element '" + e.name + "': " + message);
  };
  for (std::size_t k = 0; k < header.elements.size(); ++k) {
    Element& e = header.elements[k];
    for (std::size_t before = 0; before < k; ++before)
      if (header.elements[before].name == e.name)
        fail(e, "declared a second time (the first is on line " + std::to_string(header.elements[before].headerLine) + ")");
    for (std::size_t p = 0; p < e.properties.size(); ++p)
      for (std::size_t q = 0; q < p; ++q)
        if (e.properties[q].name == e.properties[p].name) fail(e, "property '" + e.properties[p].name + "' is declared twice");
    if (e.count > 0 && e.properties.empty()) fail(e, "has no properties");
    if (e.name == "vertex") {
      int found = 0, normals = 0;
      for (Property& p : e.properties) {
        static constexpr std::pair<std::string_view, Role> slots[] = {
            {"x", Role::X}, {"y", Role::Y}, {"z", Role::Z}, {"nx", Role::NX}, {"ny", Role::NY}, {"nz", Role::NZ}};
        for (const auto& [name, role] : slots)
          if (p.name == name) {
            if (p.isList) fail(e, "property '" + p.name + "' must not be a list");
            p.role = role;
            (role == Role::X || role == Role::Y || role == Role::Z ? found : normals) += 1;
          }
      }
      if (found != 3) fail(e, "needs the properties x, y and z");
      hasNormals = normals == 3;
    } else if (e.name == "face") {
      int lists = 0;
      for (Property& p : e.properties)
        if (p.name == "vertex_indices" || p.name == "vertex_index") {
          if (!p.isList || !isInteger(p.type)) fail(e, "'" + p.name + "' must be a list of integers");
          p.role = Role::FaceIndices;
          ++lists;
        }
      if (lists == 0) fail(e, "needs a 'vertex_indices' list");
      if (lists > 1) fail(e, "has both 'vertex_indices' and 'vertex_index' (one list of vertex indices)");
    } else if (e.name == "edge") {
      bool first = false, second = false;
      for (Property& p : e.properties) {
        if (p.name == "vertex1") p.role = Role::Edge0, first = true;
        if (p.name == "vertex2") p.role = Role::Edge1, second = true;
        if (p.role != Role::Ignore && (p.isList || !isInteger(p.type))) fail(e, "'" + p.name + "' must be an integer");
      }
      if (!first || !second) fail(e, std::string("needs the properties vertex1 and vertex2 (") + (first ? "vertex2" : second ? "vertex1" : "both") + " missing)");
    } else if (e.name == "tristrips" && e.count > 0) {
      fail(e, "triangle strips are not read (convert them to a 'face' element)");
    }
  }
  if (std::none_of(header.elements.begin(), header.elements.end(), [](const Element& e) { return e.name == "vertex"; }))
    throw MeshIoError(source + ": a PLY mesh needs a 'vertex' element");
}

// The fewest bytes one element can take, so that a count can be checked before allocating.
std::size_t minimumBytes(const Element& e, Encoding encoding) {
  std::size_t bytes = 0;
  for (const Property& p : e.properties)
    bytes += encoding == Encoding::Ascii ? 2 : (p.isList ? sizeOf(p.countType) : sizeOf(p.type));
  return bytes;
}

// The data section: one value source for ASCII and binary, with the element's name in errors.
class DataReader {
 public:
  /// `base`: where `bytes` start in the file (the cells of a file read in slices), for messages.
  DataReader(std::string_view bytes, const Header& header, const std::string& source, std::size_t base = 0)
      : encoding_(header.encoding),
        text_(bytes.substr(header.dataOffset), source, header.dataLine),
        bytes_(bytes, source, header.dataOffset, base) {}

  template <class T>
  T value(Type type, const Where& where) {
    if (encoding_ == Encoding::Ascii) {
      text_.skipBlanks();
      // Values may wrap onto following lines in some writers; each element ends its line.
      while (!text_.atEnd() && text_.atLineEnd()) {
        text_.nextLine();
        text_.skipBlanks();
      }
      if (text_.atEnd()) text_.fail(where.text() + ": the file ends early");
      if (isInteger(type)) return T(asciiInteger(type, where));
      if (type == Type::Float32) return T(text_.number<float>(where));
      return T(text_.number<double>(where));
    }
    const bool big = encoding_ == Encoding::Big;
    bytes_.need(sizeOf(type), where);
    switch (type) {
      case Type::Int8: return T(bytes_.take<std::int8_t>(big));
      case Type::UInt8: return T(bytes_.take<std::uint8_t>(big));
      case Type::Int16: return T(bytes_.take<std::int16_t>(big));
      case Type::UInt16: return T(bytes_.take<std::uint16_t>(big));
      case Type::Int32: return T(bytes_.take<std::int32_t>(big));
      case Type::UInt32: return T(bytes_.take<std::uint32_t>(big));
      case Type::Float32: {
        const float v = bytes_.take<float>(big);
        if (!std::isfinite(v)) bytes_.fail(where.text() + ": non-finite number");
        return T(v);
      }
      case Type::Float64: {
        const double v = bytes_.take<double>(big);
        if (!std::isfinite(v)) bytes_.fail(where.text() + ": non-finite number");
        return T(v);
      }
    }
    return T();
  }

  /// The binary data's cursor (the fast paths read through it directly).
  ByteCursor& binary() { return bytes_; }

  /// Bytes (binary) or characters (ASCII) not yet read.
  std::size_t bytesLeft() const { return encoding_ == Encoding::Ascii ? text_.bytesLeft() : bytes_.bytesLeft(); }

  /// ASCII: an element ends its line.
  void endElement(const Where& where) {
    if (encoding_ == Encoding::Ascii) text_.endLine(where);
  }

  /// Fails when data are left after the last element (blank lines in ASCII are fine).
  void expectEnd() {
    if (encoding_ == Encoding::Ascii) {
      while (!text_.atEnd()) {
        text_.skipBlanks();
        if (!text_.atLineEnd()) text_.fail("data after the last element");
        text_.nextLine();
      }
    } else if (bytes_.bytesLeft() != 0) {
      bytes_.fail(std::to_string(bytes_.bytesLeft()) + " bytes after the last element");
    }
  }

  [[noreturn]] void fail(const std::string& message) const {
    if (encoding_ == Encoding::Ascii) text_.fail(message);
    bytes_.fail(message);
  }

 private:
  long long asciiInteger(Type type, const Where& where) {
    static constexpr std::pair<long long, long long> ranges[] = {
        {-128, 127}, {0, 255}, {-32768, 32767}, {0, 65535}, {INT_MIN, INT_MAX}, {0, 4294967295LL}};
    const auto [lo, hi] = ranges[int(type)];
    return text_.integer(where, lo, hi);
  }

  Encoding encoding_;
  TextCursor text_;
  ByteCursor bytes_;
};

bool isFixedSize(const Element& e) {
  return std::none_of(e.properties.begin(), e.properties.end(), [](const Property& p) { return p.isList; });
}

// One binary value of `type` at `at` as a double (byte-swapped when `swap`).
double loadValue(Type type, const char* at, bool swap) {
  auto load = [&](auto value) {
    char raw[sizeof(value)];
    std::memcpy(raw, at, sizeof(value));
    if (swap) std::reverse(raw, raw + sizeof(value));
    std::memcpy(&value, raw, sizeof(value));
    return double(value);
  };
  switch (type) {
    case Type::Int8: return load(std::int8_t());
    case Type::UInt8: return load(std::uint8_t());
    case Type::Int16: return load(std::int16_t());
    case Type::UInt16: return load(std::uint16_t());
    case Type::Int32: return load(std::int32_t());
    case Type::UInt32: return load(std::uint32_t());
    case Type::Float32: return load(float());
    case Type::Float64: return load(double());
  }
  return 0.0;
}

// The binary records of vertices [first, first + count) of `e` (scalar properties only), from
// `at`, into rows 0..count-1 of `points`; every number is checked finite and a failure names
// the vertex by its index in the file. float32 records (nearly every file) skip the per-value
// dispatch.
void decodeVertices(const Element& e, bool big, const char* at, long long first, long long count,
                    Eigen::MatrixX3d& points, const ByteCursor& errors) {
  const bool swap = big != (std::endian::native == std::endian::big);
  const std::size_t stride = minimumBytes(e, Encoding::Little);
  std::vector<int> column(e.properties.size());
  std::vector<std::size_t> offset(e.properties.size());
  bool allFloat = true;
  for (std::size_t k = 0, o = 0; k < e.properties.size(); o += sizeOf(e.properties[k].type), ++k) {
    const Role r = e.properties[k].role;
    column[k] = r == Role::X ? 0 : r == Role::Y ? 1 : r == Role::Z ? 2 : -1;
    offset[k] = o;
    allFloat = allFloat && e.properties[k].type == Type::Float32;
  }
  auto fail = [&](long long i, std::size_t k) {
    errors.fail(Where{"vertex", first + i, e.properties[k].name}.text() + ": non-finite number");
  };
  // Coordinate c of vertex i at out[c * rows + i] (column-major): plain stores, as clang under
  // UBSan leaves Eigen's element access as a call per value.
  double* const out = points.data();
  const Eigen::Index rows = points.rows();
  if (allFloat) {
    for (long long i = 0; i < count; ++i, at += stride)
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        std::uint32_t w;
        std::memcpy(&w, at + 4 * k, 4);
        const float v = std::bit_cast<float>(swap ? __builtin_bswap32(w) : w);  // std::byteswap is C++23
        if (!std::isfinite(v)) fail(i, k);
        if (column[k] >= 0) out[column[k] * rows + i] = v;
      }
    return;
  }
  for (long long i = 0; i < count; ++i, at += stride)
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const double v = loadValue(e.properties[k].type, at + offset[k], swap);
      if (!std::isfinite(v)) fail(i, k);
      if (column[k] >= 0) out[column[k] * rows + i] = v;
    }
}

// The layouts nearly every binary file uses, read without a per-value dispatch: vertices of
// scalar properties (decodeVertices), and faces of one "list uchar int" property. Same checks as the
// general path: bytes before reading, finiteness, index range. Returns false for other layouts.
bool readBinaryFast(const Element& e, bool big, ByteCursor& data, MeshData& mesh, TriangleSink& triangles, long long vertices) {
  const bool swap = big != (std::endian::native == std::endian::big);
  auto word = [&](const char* at) {
    std::uint32_t w;
    std::memcpy(&w, at, 4);
    return swap ? __builtin_bswap32(w) : w;  // std::byteswap is C++23
  };
  if (e.name == "vertex") {
    if (!isFixedSize(e)) return false;
    const std::size_t stride = minimumBytes(e, Encoding::Little);
    data.need(std::size_t(e.count) * stride, {"vertex", e.count - 1});
    decodeVertices(e, big, data.here(), 0, e.count, mesh.points, data);
    data.skip(std::size_t(e.count) * stride);
    return true;
  }
  if (e.name == "face") {
    if (e.properties.size() != 1) return false;
    const Property& p = e.properties[0];
    if (p.role != Role::FaceIndices || p.countType != Type::UInt8 || (p.type != Type::Int32 && p.type != Type::UInt32)) return false;
    // vertices <= INT_MAX, so one unsigned compare rejects a negative int32 index too.
    const std::uint32_t vertexCount = std::uint32_t(vertices);
    for (long long i = 0; i < e.count; ++i) {
      // A run of triangles (count byte 3, nearly every face of nearly every file) as 13-byte
      // records, without a call per face; the first face that is not a triangle with indices in
      // range, or too near the end, goes through the general code below, which says what is wrong.
      for (; i < e.count && data.bytesLeft() >= 13; ++i) {
        const char* at = data.here();
        if (static_cast<unsigned char>(*at) != 3) break;
        const std::uint32_t a = word(at + 1), b = word(at + 5), c = word(at + 9);
        if ((a >= vertexCount) | (b >= vertexCount) | (c >= vertexCount)) break;
        triangles.add(int(a), int(b), int(c));
        data.skip(13);
      }
      if (i == e.count) break;
      data.need(1, {"face", i, p.name});
      const int n = static_cast<unsigned char>(*data.here());
      data.skip(1);
      if (n < 3) data.fail(Where{"face", i}.text() + ": a face needs at least 3 vertices, it has " + std::to_string(n));
      if (std::size_t(n) * 4 > data.bytesLeft())
        data.fail(Where{"face", i, p.name}.text() + ": a list of " + std::to_string(n) + " values runs past the end of the file");
      const char* at = data.here();
      int first = 0, previous = 0;
      for (int k = 0; k < n; ++k) {
        const std::uint32_t raw = word(at + 4 * k);
        const long long index = p.type == Type::Int32 ? (long long)std::bit_cast<std::int32_t>(raw) : (long long)raw;
        if (index < 0 || index >= vertices)
          data.fail(Where{"face", i}.text() + ": vertex index " + std::to_string(index) + " is outside 0.." + std::to_string(vertices - 1));
        if (k == 0) first = int(index);
        else if (k >= 2) triangles.add(first, previous, int(index));
        previous = int(index);
      }
      data.skip(std::size_t(n) * 4);
    }
    return true;
  }
  return false;
}

// Every count against the bytes of data there are (`dataBytes`), before anything is allocated;
// returns the vertex count.
long long checkCounts(const Header& header, std::size_t dataBytes, const std::string& source) {
  std::size_t needed = 0;
  const std::size_t available = dataBytes + (header.encoding == Encoding::Ascii ? 1 : 0);
  long long vertexCount = 0;
  for (const Element& e : header.elements) {
    const std::size_t each = minimumBytes(e, header.encoding);
    if (each > 0 && std::size_t(e.count) > (available - std::min(needed, available)) / each)
      throw MeshIoError(source + ":" + std::to_string(e.headerLine) + ": element '" + e.name + "' announces " +
                        std::to_string(e.count) + " items of at least " + std::to_string(each) +
                        " bytes, the file has " + std::to_string(available - std::min(needed, available)) + " bytes of data left");
    needed += std::size_t(e.count) * each;
    if (e.name == "vertex") vertexCount = e.count;
  }
  if (vertexCount > INT_MAX) throw MeshIoError(source + ": " + std::to_string(vertexCount) + " vertices is more than ffdkit indexes");
  if (vertexCount == 0) throw MeshIoError(source + ": the file has no vertices");
  return vertexCount;
}

// The data of every element in the header's order (without the vertex element's when
// `skipVertices`: `data` then starts after it) into `mesh`, whose points are sized.
void readElements(const Header& header, DataReader& data, MeshData& mesh, long long vertexCount, bool skipVertices,
                  ReadBudget& budget) {
  TriangleSink triangles;
  SegmentSink segments;
  std::vector<long long> polygon;
  for (const Element& e : header.elements) {
    if (skipVertices && e.name == "vertex") continue;
    if (e.name == "face") triangles = TriangleSink(Eigen::Index(e.count), &budget, "element 'face' (its triangles)");
    if (e.name == "edge") segments = SegmentSink(Eigen::Index(e.count), &budget, "element 'edge'");
    if (header.encoding != Encoding::Ascii && e.count > 0 &&
        readBinaryFast(e, header.encoding == Encoding::Big, data.binary(), mesh, triangles, vertexCount))
      continue;
    const char* kind = e.name == "vertex" ? "vertex" : e.name == "face" ? "face" : e.name == "edge" ? "edge" : e.name.c_str();
    for (long long i = 0; i < e.count; ++i) {
      long long edge[2] = {-1, -1};  // assignRoles requires both
      for (const Property& p : e.properties) {
        const Where where{kind, i, p.name};
        if (p.isList) {
          const long long n = data.value<long long>(p.countType, where);
          if (n < 0) data.fail(where.text() + ": negative list count");
          // A list count is checked against the bytes left too (a 255 past the end is an error, not a read).
          const std::size_t each = header.encoding == Encoding::Ascii ? 2 : sizeOf(p.type);
          if (std::size_t(n) > (data.bytesLeft() + 1) / each)
            data.fail(where.text() + ": a list of " + std::to_string(n) + " values runs past the end of the file");
          if (p.role == Role::FaceIndices) {
            polygon.clear();
            for (long long k = 0; k < n; ++k) {
              const long long index = data.value<long long>(p.type, where);
              if (index < 0 || index >= vertexCount)
                data.fail(Where{kind, i}.text() + ": vertex index " + std::to_string(index) + " is outside 0.." +
                          std::to_string(vertexCount - 1));
              polygon.push_back(index);
            }
            if (n < 3) data.fail(Where{kind, i}.text() + ": a face needs at least 3 vertices, it has " + std::to_string(n));
            for (long long k = 1; k + 1 < n; ++k) triangles.add(int(polygon[0]), int(polygon[std::size_t(k)]), int(polygon[std::size_t(k + 1)]));
          } else {
            for (long long k = 0; k < n; ++k) (void)data.value<double>(p.type, where);
          }
          continue;
        }
        switch (p.role) {
          case Role::X: mesh.points(i, 0) = data.value<double>(p.type, where); break;
          case Role::Y: mesh.points(i, 1) = data.value<double>(p.type, where); break;
          case Role::Z: mesh.points(i, 2) = data.value<double>(p.type, where); break;
          case Role::Edge0: case Role::Edge1: {
            const long long index = data.value<long long>(p.type, where);
            if (index < 0 || index >= vertexCount)
              data.fail(Where{kind, i}.text() + ": vertex index " + std::to_string(index) + " is outside 0.." +
                        std::to_string(vertexCount - 1));
            edge[p.role == Role::Edge0 ? 0 : 1] = index;
            break;
          }
          default: (void)data.value<double>(p.type, where); break;  // normals are recomputed on write
        }
      }
      if (e.name == "edge") segments.add(int(edge[0]), int(edge[1]));
      data.endElement({kind, i});
    }
  }
  data.expectEnd();
  mesh.triangles = triangles.take();
  mesh.segments = segments.take();
}

}  // namespace

MeshData readPly(std::string_view bytes, const std::string& source, ReadBudget& budget) {
  Header header = readHeader(bytes, source);
  MeshData mesh;
  assignRoles(header, source, mesh.hasNormals);
  const long long vertexCount = checkCounts(header, bytes.size() - header.dataOffset, source);
  budget.chargePoints(std::uint64_t(vertexCount), "element 'vertex'");
  mesh.points.resize(Eigen::Index(vertexCount), 3);
  adviseHugePages(mesh.points);
  DataReader data(bytes, header, source);
  readElements(header, data, mesh, vertexCount, false, budget);
  return mesh;
}

std::string plyHeader(Eigen::Index vertices, bool normals, Eigen::Index triangles, Eigen::Index segments, PlyEncoding encoding) {
  const bool ascii = encoding == PlyEncoding::Ascii;
  std::string out = "ply\nformat ";
  out += ascii ? "ascii" : encoding == PlyEncoding::BinaryBigEndian ? "binary_big_endian" : "binary_little_endian";
  out += " 1.0\ncomment ffdkit\nelement vertex " + std::to_string(vertices) + "\n";
  // ASCII keeps doubles (shortest text, exact); binary files keep float32, as most tools expect.
  const char* real = ascii ? "double" : "float";
  for (const char* axis : {"x", "y", "z"}) out.append("property ").append(real).append(" ").append(axis).append("\n");
  if (normals)
    for (const char* axis : {"nx", "ny", "nz"}) out.append("property float ").append(axis).append("\n");
  if (triangles > 0)
    out += "element face " + std::to_string(triangles) + "\nproperty list uchar int vertex_indices\n";
  if (segments > 0)
    out += "element edge " + std::to_string(segments) + "\nproperty int vertex1\nproperty int vertex2\n";
  out += "end_header\n";
  return out;
}

void writePly(ByteSink& sink, const MeshData& mesh, PlyEncoding encoding) {
  const bool normals = mesh.hasNormals && mesh.triangles.rows() > 0;
  const Eigen::MatrixX3d n = normals ? vertexNormals(mesh.points, mesh.triangles) : Eigen::MatrixX3d();
  const bool ascii = encoding == PlyEncoding::Ascii;
  const std::string header = plyHeader(mesh.points.rows(), normals, mesh.triangles.rows(), mesh.segments.rows(), encoding);

  if (ascii) {
    std::string out = header;
    for (Eigen::Index i = 0; i < mesh.points.rows(); ++i) {
      for (int c = 0; c < 3; ++c) {
        if (c > 0) out += ' ';
        appendNumber(out, mesh.points(i, c));
      }
      for (int c = 0; normals && c < 3; ++c) {
        out += ' ';
        appendNumber(out, float(n(i, c)));
      }
      out += '\n';
    }
    for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
      out += '3';
      for (int c = 0; c < 3; ++c) {
        out += ' ';
        appendNumber(out, (long long)mesh.triangles(t, c));
      }
      out += '\n';
    }
    for (Eigen::Index s = 0; s < mesh.segments.rows(); ++s) {
      appendNumber(out, (long long)mesh.segments(s, 0));
      out += ' ';
      appendNumber(out, (long long)mesh.segments(s, 1));
      out += '\n';
    }
    sink.write(out);
    return;
  }

  // Binary: fixed-size records streamed through one small buffer.
  const bool big = encoding == PlyEncoding::BinaryBigEndian;
  BinaryChunks chunks(sink);
  chunks.bytes(header);
  writePlyVertices(chunks, mesh.points, normals ? &n : nullptr, big);
  writePlyCells(chunks, mesh.triangles, mesh.segments, big);
  chunks.flush();
}

void writePlyVertices(BinaryChunks& chunks, const Eigen::MatrixX3d& points, const Eigen::MatrixX3d* normals, bool big) {
  chunks.records(points.rows(), normals ? 2 * kPlyVertexBytes : kPlyVertexBytes, [&](char* at, Eigen::Index i) {
    for (int c = 0; c < 3; ++c) at = storeBinary(at, float(points(i, c)), big);
    for (int c = 0; normals && c < 3; ++c) at = storeBinary(at, float((*normals)(i, c)), big);
  });
}

void writePlyCells(BinaryChunks& chunks, const Eigen::MatrixX3i& triangles, const Eigen::MatrixX2i& segments, bool big) {
  chunks.records(triangles.rows(), kPlyTriangleBytes, [&](char* at, Eigen::Index t) {
    *at++ = 3;
    for (int c = 0; c < 3; ++c) at = storeBinary(at, std::int32_t(triangles(t, c)), big);
  });
  chunks.records(segments.rows(), kPlyEdgeBytes, [&](char* at, Eigen::Index s) {
    for (int c = 0; c < 2; ++c) at = storeBinary(at, std::int32_t(segments(s, c)), big);
  });
}

}  // namespace ffdkit::meshio::detail

namespace ffdkit::meshio::detail {

struct PlySlices::Layout {
  Header header;
  std::size_t vertexElement = 0;
  bool hasNormals = false;
};

PlySlices::PlySlices(std::string_view prefix, std::uint64_t fileBytes, const std::string& source)
    : layout_(std::make_unique<Layout>()), source_(source) {
  Header& header = layout_->header;
  header = readHeader(prefix, source);
  assignRoles(header, source, layout_->hasNormals);
  vertexCount_ = checkCounts(header, std::size_t(fileBytes) - header.dataOffset, source);
  auto refuse = [&](const std::string& why) {
    throw MeshIoError(source + ": cannot be read in slices of vertices: " + why);
  };
  if (header.encoding == Encoding::Ascii) refuse("an ASCII PLY has no fixed-size vertex records (write it as binary PLY)");
  std::size_t& v = layout_->vertexElement;
  while (header.elements[v].name != "vertex") {
    if (header.elements[v].count > 0) refuse("element '" + header.elements[v].name + "' comes before the vertices");
    ++v;
  }
  if (!isFixedSize(header.elements[v])) refuse("a vertex property is a list");
  recordBytes_ = minimumBytes(header.elements[v], header.encoding);
  vertexOffset_ = header.dataOffset;
  cellsOffset_ = vertexOffset_ + std::uint64_t(vertexCount_) * recordBytes_;
  for (const Element& e : header.elements) {
    if (e.name == "face") faceCount_ += e.count;
    if (&e > &header.elements[v] && e.count > 0) hasCells_ = true;
  }
}

PlySlices::~PlySlices() = default;

bool PlySlices::hasNormals() const { return layout_->hasNormals; }

void PlySlices::decode(std::string_view records, long long first, Eigen::MatrixX3d& points) const {
  const long long count = points.rows();
  if (first < 0 || count < 0 || first + count > vertexCount_ || records.size() != std::size_t(count) * recordBytes_)
    throw std::logic_error(source_ + ": vertex slice out of range");
  const ByteCursor errors(records, source_, 0, std::size_t(vertexOffset_ + std::uint64_t(first) * recordBytes_));
  decodeVertices(layout_->header.elements[layout_->vertexElement], layout_->header.encoding == Encoding::Big,
                 records.data(), first, count, points, errors);
}

MeshData PlySlices::readCells(std::string_view tail, ReadBudget& budget) const {
  Header header = layout_->header;
  header.dataOffset = 0;
  DataReader data(tail, header, source_, std::size_t(cellsOffset_));
  MeshData cells;
  readElements(header, data, cells, vertexCount_, true, budget);
  return cells;
}

}  // namespace ffdkit::meshio::detail
