#include "vtk_xml_block_headers.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <optional>

#include "ffdkit/meshio/mesh_io.h"

namespace ffdkit::meshio::detail {
namespace {

// The value of `name="..."` (or '...') inside one tag's text, if present.
std::optional<std::string_view> attribute(std::string_view tag, std::string_view name) {
  for (std::size_t at = tag.find(name); at != std::string_view::npos; at = tag.find(name, at + 1)) {
    const bool wordStart = at > 0 && (tag[at - 1] == ' ' || tag[at - 1] == '\t' || tag[at - 1] == '\n' || tag[at - 1] == '\r');
    std::size_t eq = at + name.size();
    while (eq < tag.size() && (tag[eq] == ' ' || tag[eq] == '\t')) ++eq;
    if (!wordStart || eq >= tag.size() || tag[eq] != '=') continue;
    std::size_t quote = eq + 1;
    while (quote < tag.size() && (tag[quote] == ' ' || tag[quote] == '\t')) ++quote;
    if (quote >= tag.size() || (tag[quote] != '"' && tag[quote] != '\'')) return std::nullopt;
    const std::size_t end = tag.find(tag[quote], quote + 1);
    if (end == std::string_view::npos) return std::nullopt;
    return tag.substr(quote + 1, end - quote - 1);
  }
  return std::nullopt;
}

// The tag starting at `open` ('<'), up to its '>' (or the end of the bytes).
std::string_view tagAt(std::string_view bytes, std::size_t open) {
  const std::size_t close = bytes.find('>', open);
  return bytes.substr(open, close == std::string_view::npos ? std::string_view::npos : close - open);
}

int base64Value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  if (c == '=') return 0;  // padding
  return -1;
}

// The first `count` bytes of the base64 stream at `text` as VTK's vtkBase64InputStream reads
// them: 4 characters give 3 bytes, or 1 ("xx=?") or 2 ("xxx=") where padded, and the stream
// ends after a padded group or at a character that is not base64. nullopt if it ends first.
std::optional<std::string> base64Prefix(std::string_view text, std::size_t count) {
  std::string out;
  out.reserve(count + 2);
  for (std::size_t i = 0; out.size() < count; i += 4) {
    if (i + 4 > text.size()) return std::nullopt;
    std::uint32_t group = 0;
    for (std::size_t k = 0; k < 4; ++k) {
      const int v = base64Value(text[i + k]);
      if (v < 0) return std::nullopt;
      group = group << 6 | std::uint32_t(v);
    }
    const int bytes = text[i + 2] == '=' ? 1 : text[i + 3] == '=' ? 2 : 3;
    const char decoded[3] = {char(group >> 16), char(group >> 8 & 0xff), char(group & 0xff)};
    out.append(decoded, std::size_t(bytes));
    if (bytes < 3 && out.size() < count) return std::nullopt;
  }
  return out;
}

struct HeaderLayout {
  std::size_t wordSize = 4;  // header_type UInt32 (the default) or UInt64
  bool bigEndian = false;
};

std::uint64_t word(std::string_view raw, std::size_t index, const HeaderLayout& layout) {
  std::uint64_t value = 0;
  for (std::size_t b = 0; b < layout.wordSize; ++b) {
    const std::size_t at = index * layout.wordSize + (layout.bigEndian ? b : layout.wordSize - 1 - b);
    value = value << 8 | static_cast<unsigned char>(raw[at]);
  }
  return value;
}

std::size_t lineOf(std::string_view bytes, std::size_t offset) {
  return 1 + std::size_t(std::count(bytes.begin(), bytes.begin() + std::ptrdiff_t(offset), '\n'));
}

}  // namespace

void checkVtkXmlBlockHeaders(std::string_view bytes, const std::string& source) {
  const std::size_t root = bytes.find("<VTKFile");
  if (root == std::string_view::npos) return;
  const std::string_view rootTag = tagAt(bytes, root);
  const auto compressor = attribute(rootTag, "compressor");
  if (!compressor || compressor->empty()) return;  // uncompressed: a header of one word, the data's size
  HeaderLayout layout;
  if (attribute(rootTag, "header_type") == std::string_view("UInt64")) layout.wordSize = 8;
  layout.bigEndian = attribute(rootTag, "byte_order") == std::string_view("BigEndian");

  // Where appended data start (after the '_' that follows the AppendedData tag) and how they
  // are encoded; DataArray tags all come before it (raw appended bytes are not XML).
  std::size_t appendedTag = bytes.find("<AppendedData");
  std::size_t appendedStart = std::string_view::npos;
  bool appendedBase64 = false;
  if (appendedTag != std::string_view::npos) {
    const std::string_view tag = tagAt(bytes, appendedTag);
    appendedBase64 = attribute(tag, "encoding") == std::string_view("base64");
    const std::size_t underscore = bytes.find('_', appendedTag + tag.size());
    if (underscore != std::string_view::npos) appendedStart = underscore + 1;
  } else {
    appendedTag = bytes.size();
  }

  const std::uint64_t blockSizeLimit = std::max<std::uint64_t>(std::uint64_t(1) << 24, 1100 * std::uint64_t(bytes.size()));
  const std::string_view text = bytes.substr(0, appendedTag);
  for (std::size_t at = text.find("<DataArray"); at != std::string_view::npos; at = text.find("<DataArray", at + 1)) {
    const std::string_view tag = tagAt(text, at);
    const auto format = attribute(tag, "format");
    // The header's bytes from `count` on: the 3 standard words, then one compressed size per block.
    std::string_view inlineText, appendedData;
    if (format == std::string_view("binary")) {
      std::size_t start = at + tag.size() + 1;
      while (start < text.size() && (text[start] == ' ' || text[start] == '\n' || text[start] == '\r' || text[start] == '\t')) ++start;
      if (start >= text.size()) continue;
      inlineText = text.substr(start);
    } else if (format == std::string_view("appended") && appendedStart != std::string_view::npos) {
      const auto offsetText = attribute(tag, "offset");
      std::uint64_t offset = 0;
      if (!offsetText || std::from_chars(offsetText->data(), offsetText->data() + offsetText->size(), offset).ec != std::errc() ||
          offset > bytes.size() - appendedStart)
        continue;  // VTK reports a bad offset itself
      appendedData = bytes.substr(appendedStart + std::size_t(offset));
    } else {
      continue;  // ASCII, or appended without an AppendedData element: VTK reports it
    }
    const bool base64 = !inlineText.empty() || appendedBase64;
    const auto headerBytes = [&](std::size_t words) -> std::optional<std::string> {
      const std::size_t count = words * layout.wordSize;
      if (base64) return base64Prefix(inlineText.empty() ? appendedData : inlineText, count);
      if (appendedData.size() < count) return std::nullopt;
      return std::string(appendedData.substr(0, count));
    };
    const auto standard = headerBytes(3);
    if (!standard) continue;  // too short: VTK reports the header unread
    const std::uint64_t blocks = word(*standard, 0, layout);
    const std::uint64_t blockSize = word(*standard, 1, layout);
    const std::uint64_t lastBlockSize = word(*standard, 2, layout);
    const std::string where = source + ":" + std::to_string(lineOf(bytes, at)) + ": DataArray \"" +
                              std::string(attribute(tag, "Name").value_or("")) + "\": ";
    const std::string ofTheFile = "a file of " + std::to_string(bytes.size()) + " bytes";
    // VTK divides by the block size and indexes blocks by the last one's size: a header it can
    // use has blocks of at least a byte, a last block no larger than the others, and no last
    // block without blocks (fuzz_mesh_vtp: a block size of 0 made VTK divide by zero).
    if ((blocks > 0 && blockSize == 0) || lastBlockSize > blockSize || (blocks == 0 && lastBlockSize != 0))
      throw MeshIoError(where + "its compression header is inconsistent (" + std::to_string(blocks) + " blocks of " +
                        std::to_string(blockSize) + " bytes, the last of " + std::to_string(lastBlockSize) + ")");
    if (blocks > bytes.size() / layout.wordSize)
      throw MeshIoError(where + "its compression header announces " + std::to_string(blocks) + " blocks, more than " + ofTheFile +
                        " can list");
    if (blockSize > blockSizeLimit || lastBlockSize > blockSizeLimit)
      throw MeshIoError(where + "its compression header announces blocks of " + std::to_string(std::max(blockSize, lastBlockSize)) +
                        " bytes, more than " + ofTheFile + " can decompress to");
    // Each block's compressed size: VTK allocates it before reading the block.
    const auto whole = headerBytes(3 + std::size_t(blocks));
    if (!whole) continue;  // sizes missing: VTK reports the header unread
    for (std::uint64_t b = 0; b < blocks; ++b)
      if (const std::uint64_t size = word(*whole, 3 + std::size_t(b), layout); size > bytes.size())
        throw MeshIoError(where + "block " + std::to_string(b) + " announces " + std::to_string(size) + " compressed bytes, more than " +
                          ofTheFile + " holds");
  }
}

}  // namespace ffdkit::meshio::detail
