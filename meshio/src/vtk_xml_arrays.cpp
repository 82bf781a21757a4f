#include "vtk_xml_arrays.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <string_view>

#include <fast_float/fast_float.h>
#include <lz4.h>
#include <lzma.h>
#include <zlib.h>

#include "ffdkit/meshio/mesh_data.h"

namespace ffdkit::meshio::detail {
namespace {

struct ScalarType {
  std::size_t size;
  bool isFloat;
  bool isSigned;
};

std::optional<ScalarType> scalarType(std::string_view name) {
  if (name == "Float64") return ScalarType{8, true, true};
  if (name == "Float32") return ScalarType{4, true, true};
  if (name == "Int64") return ScalarType{8, false, true};
  if (name == "UInt64") return ScalarType{8, false, false};
  if (name == "Int32") return ScalarType{4, false, true};
  if (name == "UInt32") return ScalarType{4, false, false};
  if (name == "Int16") return ScalarType{2, false, true};
  if (name == "UInt16") return ScalarType{2, false, false};
  if (name == "Int8") return ScalarType{1, false, true};
  if (name == "UInt8") return ScalarType{1, false, false};
  return std::nullopt;
}

// A byte stream over raw data or base64 text. base64 as VTK's vtkBase64InputStream reads it:
// 4 characters give 3 bytes, or 1 ("xx==") or 2 ("xxx=") where padded, and the stream ends
// after a padded group or at a character that is not base64.
class EncodedStream {
 public:
  EncodedStream(std::string_view data, bool base64) : data_(data), base64_(base64) {}

  /// At most this many bytes can still be read.
  std::size_t maxBytesLeft() const {
    if (!base64_) return data_.size() - pos_;
    return ended_ ? pendingCount_ - pendingPos_ : (data_.size() - pos_) / 4 * 3 + (pendingCount_ - pendingPos_);
  }

  /// The next `n` bytes into `out`; false if the stream ends first.
  bool read(std::size_t n, unsigned char* out) {
    if (n == 0) return true;  // `out` may be null (an empty vector's data)
    if (!base64_) {
      if (n > data_.size() - pos_) return false;
      std::memcpy(out, data_.data() + pos_, n);
      pos_ += n;
      return true;
    }
    while (n > 0) {
      if (pendingPos_ < pendingCount_) {
        const std::size_t take = std::min(n, pendingCount_ - pendingPos_);
        std::memcpy(out, pending_.data() + pendingPos_, take);
        pendingPos_ += take, out += take, n -= take;
        continue;
      }
      if (ended_) return false;
      // Whole groups straight into `out`: unpadded ones in a tight loop, then one at a time
      // (padding, the end); the last partial group goes through `pending_`.
      while (n >= 3 && data_.size() - pos_ >= 4) {
        const auto* g = reinterpret_cast<const unsigned char*>(data_.data() + pos_);
        const int a = kValue[g[0]], b = kValue[g[1]], c = kValue[g[2]], d = kValue[g[3]];
        if ((a | b | c | d) < 0) break;
        const std::uint32_t group = std::uint32_t(a) << 18 | std::uint32_t(b) << 12 | std::uint32_t(c) << 6 | std::uint32_t(d);
        out[0] = static_cast<unsigned char>(group >> 16);
        out[1] = static_cast<unsigned char>(group >> 8);
        out[2] = static_cast<unsigned char>(group);
        pos_ += 4, out += 3, n -= 3;
      }
      while (n >= 3 && !ended_) {
        const int got = decodeGroup(out);
        if (got < 0) return false;
        out += got, n -= std::size_t(got);
      }
      if (n > 0 && !ended_) {
        const int got = decodeGroup(pending_.data());
        if (got < 0) return false;
        pendingCount_ = std::size_t(got);
        pendingPos_ = 0;
      }
    }
    return true;
  }

  /// Starts a new base64 stream at the next 4-character group: the rest of the current group
  /// is dropped (VTK encodes a compressed array's header and its blocks as two streams).
  void restart() {
    pendingCount_ = 0;
    pendingPos_ = 0;
    ended_ = false;
  }

 private:
  // The 6-bit value of each base64 character; -1 for the rest ('=' included).
  static constexpr std::array<std::int8_t, 256> kValue = [] {
    std::array<std::int8_t, 256> table{};
    table.fill(-1);
    for (int i = 0; i < 26; ++i) table['A' + i] = std::int8_t(i), table['a' + i] = std::int8_t(26 + i);
    for (int i = 0; i < 10; ++i) table['0' + i] = std::int8_t(52 + i);
    table['+'] = 62;
    table['/'] = 63;
    return table;
  }();
  static int value(char c) { return kValue[static_cast<unsigned char>(c)]; }

  // Decodes the group at pos_ into out[0..3); returns the bytes it gave, or -1 at the end.
  int decodeGroup(unsigned char* out) {
    if (data_.size() - pos_ < 4) {
      ended_ = true;
      return -1;
    }
    const char* g = data_.data() + pos_;
    const int a = value(g[0]), b = value(g[1]);
    const int c = g[2] == '=' ? 0 : value(g[2]), d = g[3] == '=' ? 0 : value(g[3]);
    if (a < 0 || b < 0 || c < 0 || d < 0 || (g[2] == '=' && g[3] != '=')) {
      ended_ = true;
      return -1;
    }
    pos_ += 4;
    const std::uint32_t group = std::uint32_t(a) << 18 | std::uint32_t(b) << 12 | std::uint32_t(c) << 6 | std::uint32_t(d);
    out[0] = static_cast<unsigned char>(group >> 16);
    out[1] = static_cast<unsigned char>(group >> 8);
    out[2] = static_cast<unsigned char>(group);
    const int bytes = g[2] == '=' ? 1 : g[3] == '=' ? 2 : 3;
    if (bytes < 3) ended_ = true;
    return bytes;
  }

  std::string_view data_;
  bool base64_;
  std::size_t pos_ = 0;
  std::array<unsigned char, 3> pending_{};  // a group's decoded bytes not read yet: [pendingPos_, pendingCount_)
  std::size_t pendingCount_ = 0;
  std::size_t pendingPos_ = 0;
  bool ended_ = false;
};

// One array's decoding context: where it is, for messages.
struct ArrayContext {
  const VtkXmlDocument& document;
  const VtkXmlDataLayout& layout;
  const XmlElement& array;
  const std::string& source;

  [[noreturn]] void fail(const std::string& message) const {
    throw MeshIoError(document.where(source, array) + "DataArray \"" + std::string(array.attribute("Name").value_or("")) + "\": " +
                      message);
  }
  std::string ofTheFile() const { return "a file of " + std::to_string(document.bytes.size()) + " bytes"; }
};

std::uint64_t headerWord(const unsigned char* raw, const VtkXmlDataLayout& layout) {
  std::uint64_t value = 0;
  for (std::size_t b = 0; b < layout.headerWordSize; ++b)
    value = value << 8 | raw[layout.bigEndian ? b : layout.headerWordSize - 1 - b];
  return value;
}

// The most a file's compressed data can expand to: zlib expands at most 1032:1, LZ4 255:1;
// LZMA could go further, but no mesh's data compress that well.
std::uint64_t decompressedLimit(std::size_t fileBytes) {
  return std::max<std::uint64_t>(std::uint64_t(64) << 20, 1100 * std::uint64_t(fileBytes));
}

bool decompress(VtkXmlDataLayout::Compressor compressor, const unsigned char* in, std::size_t inSize, unsigned char* out,
                std::size_t outSize) {
  switch (compressor) {
    case VtkXmlDataLayout::Compressor::ZLib: {
      uLongf produced = outSize;
      return uncompress(out, &produced, in, uLong(inSize)) == Z_OK && produced == outSize;
    }
    case VtkXmlDataLayout::Compressor::LZ4:
      if (inSize > INT_MAX || outSize > INT_MAX) return false;
      return LZ4_decompress_safe(reinterpret_cast<const char*>(in), reinterpret_cast<char*>(out), int(inSize), int(outSize)) ==
             int(outSize);
    case VtkXmlDataLayout::Compressor::LZMA: {
      std::uint64_t memoryLimit = std::uint64_t(256) << 20;
      std::size_t inPos = 0, outPos = 0;
      return lzma_stream_buffer_decode(&memoryLimit, 0, nullptr, in, &inPos, inSize, out, &outPos, outSize) == LZMA_OK &&
             outPos == outSize;
    }
    case VtkXmlDataLayout::Compressor::None: break;
  }
  return false;
}

// Exactly `needed` bytes of a binary array's data, in the file's byte order, charged to both of
// `budget`'s budgets before they are allocated (the caller gives `held` back: releaseDecoded).
std::vector<unsigned char> binaryBytes(const ArrayContext& context, std::size_t needed, ArrayBudget& budget) {
  const auto charge = [&](std::uint64_t bytes) {
    try {
      budget.decoded.chargeBytes(bytes, 1, "decoded data (every piece's arrays count, also where they share a block)");
      budget.held.chargeBytes(bytes, 1, "decoded data");
    } catch (const ReadLimitError& e) {
      context.fail(e.what());
    }
  };
  const VtkXmlDataLayout& layout = context.layout;
  const auto format = context.array.attribute("format");
  std::string_view data;
  bool base64 = true;
  if (format == std::string_view("binary")) {
    data = context.array.text;
    while (!data.empty() && (data.front() == ' ' || data.front() == '\n' || data.front() == '\r' || data.front() == '\t'))
      data.remove_prefix(1);
  } else {  // appended
    const auto offsetText = context.array.attribute("offset").value_or("");
    std::uint64_t offset = 0;
    const auto r = std::from_chars(offsetText.data(), offsetText.data() + offsetText.size(), offset);
    if (r.ec != std::errc() || r.ptr != offsetText.data() + offsetText.size())
      context.fail("its offset \"" + std::string(offsetText) + "\" is not a number");
    if (offset > context.document.appended.size())
      context.fail("its offset " + std::to_string(offset) + " is past the " + std::to_string(context.document.appended.size()) +
                   " bytes of appended data");
    data = context.document.appended.substr(std::size_t(offset));
    base64 = context.document.appendedBase64;
  }
  EncodedStream stream(data, base64);
  const std::size_t word = layout.headerWordSize;
  std::vector<unsigned char> out;
  const auto readHeader = [&](std::size_t words, const char* what) {
    std::vector<unsigned char> raw(words * word);
    if (!stream.read(raw.size(), raw.data())) context.fail(std::string("the data end inside its ") + what);
    std::vector<std::uint64_t> values(words);
    for (std::size_t i = 0; i < words; ++i) values[i] = headerWord(raw.data() + i * word, layout);
    return values;
  };

  if (layout.compressor == VtkXmlDataLayout::Compressor::None) {
    const std::uint64_t size = readHeader(1, "header")[0];
    if (size < needed) context.fail("holds " + std::to_string(size) + " bytes, " + std::to_string(needed) + " needed");
    if (needed > stream.maxBytesLeft())
      context.fail("announces " + std::to_string(size) + " bytes, more than the " + std::to_string(stream.maxBytesLeft()) +
                   " that follow");
    charge(needed);
    out.resize(needed);
    if (!stream.read(needed, out.data())) context.fail("the data end before its " + std::to_string(needed) + " bytes");
    return out;
  }

  const auto standard = readHeader(3, "compression header");
  const std::uint64_t blocks = standard[0], blockSize = standard[1], lastBlockSize = standard[2];
  // A last block of 0 means a full one; blocks of 0 bytes, a last block larger than the
  // others or a last block without blocks are inconsistent (VTK divided by the block size).
  if ((blocks > 0 && blockSize == 0) || lastBlockSize > blockSize || (blocks == 0 && lastBlockSize != 0))
    context.fail("its compression header is inconsistent (" + std::to_string(blocks) + " blocks of " + std::to_string(blockSize) +
                 " bytes, the last of " + std::to_string(lastBlockSize) + ")");
  if (blocks > context.document.bytes.size() / word)
    context.fail("its compression header announces " + std::to_string(blocks) + " blocks, more than " + context.ofTheFile() +
                 " can list");
  const std::uint64_t limit = decompressedLimit(context.document.bytes.size());
  if (blockSize > limit)
    context.fail("its compression header announces blocks of " + std::to_string(blockSize) + " bytes, more than " +
                 context.ofTheFile() + " can decompress to");
  const std::uint64_t total = blocks == 0 ? 0 : (blocks - 1) * blockSize + (lastBlockSize != 0 ? lastBlockSize : blockSize);
  if (total < needed) context.fail("decompresses to " + std::to_string(total) + " bytes, " + std::to_string(needed) + " needed");
  if (needed > limit)
    context.fail(std::to_string(needed) + " bytes needed, more than " + context.ofTheFile() + " can decompress to");
  const auto compressedSizes = readHeader(std::size_t(blocks), "list of block sizes");
  if (base64) stream.restart();
  // The blocks that hold the `needed` bytes, decompressed whole, in one allocation.
  const std::uint64_t blocksNeeded = needed == 0 ? 0 : (needed + blockSize - 1) / blockSize;
  const std::uint64_t decompressed = std::min(total, blocksNeeded * blockSize);
  charge(decompressed);
  out.reserve(std::size_t(decompressed));

  std::vector<unsigned char> compressed;
  for (std::uint64_t b = 0; b < blocks && out.size() < needed; ++b) {
    const std::uint64_t size = compressedSizes[b];
    const std::uint64_t uncompressed = b + 1 == blocks && lastBlockSize != 0 ? lastBlockSize : blockSize;
    if (size > stream.maxBytesLeft())
      context.fail("block " + std::to_string(b) + " announces " + std::to_string(size) + " compressed bytes, more than the " +
                   std::to_string(stream.maxBytesLeft()) + " left in " + context.ofTheFile());
    compressed.resize(std::size_t(size));
    if (!stream.read(compressed.size(), compressed.data()))
      context.fail("block " + std::to_string(b) + ": the data end before its " + std::to_string(size) + " compressed bytes");
    const std::size_t at = out.size();
    out.resize(at + std::size_t(uncompressed));
    if (!decompress(layout.compressor, compressed.data(), compressed.size(), out.data() + at, std::size_t(uncompressed)))
      context.fail("block " + std::to_string(b) + " does not decompress to its " + std::to_string(uncompressed) + " bytes");
  }
  out.resize(needed);
  return out;
}

// Frees an array's decoded bytes and gives their charge back to the read's budget (the decoded
// total keeps them).
void releaseDecoded(std::vector<unsigned char>& raw, ArrayBudget& budget) {
  budget.held.releaseBytes(raw.capacity());
  std::vector<unsigned char>().swap(raw);
}

// Converts `count` raw values of `type` (file byte order) with `convert(value, index)`.
template <class Convert>
void forEachRawValue(const std::vector<unsigned char>& raw, const ScalarType& type, bool bigEndian, std::size_t count, Convert&& convert) {
  const bool swap = bigEndian != (std::endian::native == std::endian::big);
  const auto load = [&]<class T>(T*, std::size_t i) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, raw.data() + i * sizeof(T), sizeof(T));
    if (swap) std::reverse(bytes, bytes + sizeof(T));
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return value;
  };
  const auto loop = [&]<class T>(T* tag) {
    for (std::size_t i = 0; i < count; ++i) convert(load(tag, i), i);
  };
  if (type.isFloat) {
    if (type.size == 8) loop(static_cast<double*>(nullptr));
    else loop(static_cast<float*>(nullptr));
    return;
  }
  switch (type.size) {
    case 8: type.isSigned ? loop(static_cast<std::int64_t*>(nullptr)) : loop(static_cast<std::uint64_t*>(nullptr)); break;
    case 4: type.isSigned ? loop(static_cast<std::int32_t*>(nullptr)) : loop(static_cast<std::uint32_t*>(nullptr)); break;
    case 2: type.isSigned ? loop(static_cast<std::int16_t*>(nullptr)) : loop(static_cast<std::uint16_t*>(nullptr)); break;
    default: type.isSigned ? loop(static_cast<std::int8_t*>(nullptr)) : loop(static_cast<std::uint8_t*>(nullptr)); break;
  }
}

ScalarType checkedType(const ArrayContext& context) {
  const auto name = context.array.attribute("type").value_or("");
  const auto type = scalarType(name);
  if (!type) context.fail("unknown type \"" + std::string(name) + "\"");
  const auto format = context.array.attribute("format").value_or("");
  if (format != "ascii" && format != "binary" && format != "appended")
    context.fail("unknown format \"" + std::string(format) + "\" (ascii, binary or appended)");
  return *type;
}

// The ASCII values, `parse(first, last, index)` returning the end of the number it read.
template <class Parse>
void forEachAsciiValue(const ArrayContext& context, std::size_t count, Parse&& parse) {
  const std::string_view text = context.array.text;
  if (count > (text.size() + 1) / 2)
    context.fail(std::to_string(count) + " values needed, more than its " + std::to_string(text.size()) + " characters can hold");
  const char* at = text.data();
  const char* end = text.data() + text.size();
  for (std::size_t i = 0; i < count; ++i) {
    while (at < end && (*at == ' ' || *at == '\n' || *at == '\r' || *at == '\t')) ++at;
    if (at == end) context.fail("holds " + std::to_string(i) + " values, " + std::to_string(count) + " needed");
    const char* next = parse(at, end, i);
    if (next == nullptr || (next < end && *next != ' ' && *next != '\n' && *next != '\r' && *next != '\t')) {
      const char* wordEnd = at;
      while (wordEnd < end && wordEnd - at < 40 && *wordEnd != ' ' && *wordEnd != '\n' && *wordEnd != '\r' && *wordEnd != '\t')
        ++wordEnd;
      throw MeshIoError(context.source + ":" + std::to_string(context.document.lineOf(std::size_t(at - context.document.bytes.data()))) +
                        ": DataArray \"" + std::string(context.array.attribute("Name").value_or("")) + "\": value " + std::to_string(i) +
                        ": expected a number, got '" + std::string(at, wordEnd) + "'");
    }
    at = next;
  }
}

}  // namespace

VtkXmlDataLayout VtkXmlDataLayout::of(const VtkXmlDocument& document, const std::string& source) {
  VtkXmlDataLayout layout;
  const XmlElement& root = document.root;
  const auto fail = [&](const std::string& message) { throw MeshIoError(document.where(source, root) + "VTKFile: " + message); };
  if (const auto header = root.attribute("header_type")) {
    if (*header == "UInt64") layout.headerWordSize = 8;
    else if (*header != "UInt32") fail("unknown header_type \"" + std::string(*header) + "\" (UInt32 or UInt64)");
  }
  if (const auto order = root.attribute("byte_order")) {
    if (*order == "BigEndian") layout.bigEndian = true;
    else if (*order != "LittleEndian") fail("unknown byte_order \"" + std::string(*order) + "\"");
  }
  if (const auto compressor = root.attribute("compressor"); compressor && !compressor->empty()) {
    if (*compressor == "vtkZLibDataCompressor") layout.compressor = Compressor::ZLib;
    else if (*compressor == "vtkLZ4DataCompressor") layout.compressor = Compressor::LZ4;
    else if (*compressor == "vtkLZMADataCompressor") layout.compressor = Compressor::LZMA;
    else fail("unknown compressor \"" + std::string(*compressor) + "\" (zlib, LZ4 or LZMA)");
  }
  return layout;
}

std::vector<double> readRealValues(const VtkXmlDocument& document, const VtkXmlDataLayout& layout, const XmlElement& array,
                                   std::size_t count, const std::string& source, ArrayBudget& budget) {
  const ArrayContext context{document, layout, array, source};
  const ScalarType type = checkedType(context);
  std::vector<double> values;
  const auto keep = [&](double v, std::size_t i) {
    if (!std::isfinite(v)) context.fail("value " + std::to_string(i) + " is not finite");
    values[i] = v;
  };
  if (array.attribute("format") == std::string_view("ascii")) {
    forEachAsciiValue(context, count, [&](const char* first, const char* last, std::size_t i) -> const char* {
      if (values.empty()) values.resize(count);
      if (first < last && *first == '+') ++first;
      // A Float32 array's text gives floats (as VTK reads it), then widened.
      double v = 0;
      fast_float::from_chars_result r;
      if (type.isFloat && type.size == 4) {
        float f = 0;
        r = fast_float::from_chars(first, last, f);
        v = f;
      } else {
        r = fast_float::from_chars(first, last, v);
      }
      if (r.ec != std::errc()) return nullptr;
      keep(v, i);
      return r.ptr;
    });
    values.resize(count);
    return values;
  }
  if (count > std::numeric_limits<std::size_t>::max() / 8) context.fail(std::to_string(count) + " values needed, more than memory can hold");
  std::vector<unsigned char> raw = binaryBytes(context, count * type.size, budget);
  values.resize(count);
  forEachRawValue(raw, type, layout.bigEndian, count, [&](auto v, std::size_t i) { keep(double(v), i); });
  releaseDecoded(raw, budget);
  return values;
}

std::vector<std::int64_t> readIntegerValues(const VtkXmlDocument& document, const VtkXmlDataLayout& layout, const XmlElement& array,
                                            std::size_t count, const std::string& source, ArrayBudget& budget) {
  const ArrayContext context{document, layout, array, source};
  const ScalarType type = checkedType(context);
  if (type.isFloat) context.fail("an index array of type " + std::string(array.attribute("type").value_or("")) + ", not integers");
  if (count > std::numeric_limits<std::size_t>::max() / 8) context.fail(std::to_string(count) + " values needed, more than memory can hold");
  std::vector<std::int64_t> values;
  if (array.attribute("format") == std::string_view("ascii")) {
    forEachAsciiValue(context, count, [&](const char* first, const char* last, std::size_t i) -> const char* {
      if (values.empty()) values.resize(count);
      if (first < last && *first == '+') ++first;
      const auto r = std::from_chars(first, last, values[i]);
      return r.ec == std::errc() ? r.ptr : nullptr;
    });
    values.resize(count);
    return values;
  }
  std::vector<unsigned char> raw = binaryBytes(context, count * type.size, budget);
  values.resize(count);
  forEachRawValue(raw, type, layout.bigEndian, count, [&](auto v, std::size_t i) {
    if constexpr (std::is_same_v<decltype(v), std::uint64_t>) {
      if (v > std::uint64_t(std::numeric_limits<std::int64_t>::max())) context.fail("value " + std::to_string(i) + " is out of range");
    }
    if constexpr (std::is_floating_point_v<decltype(v)>) {
      context.fail("not integers");
    } else {
      values[i] = std::int64_t(v);
    }
  });
  releaseDecoded(raw, budget);
  return values;
}

}  // namespace ffdkit::meshio::detail
