#pragma once
// The values of a VTK XML DataArray, decoded by ffdkit: ASCII text, inline base64, or appended
// raw or base64 data; uncompressed or in zlib, LZ4 or LZMA blocks; header words of 32 or 64
// bits in either byte order. Every size a file announces is checked against the bytes that
// are there before anything is allocated for it, every block must decompress to exactly its
// announced size, and nothing is decoded past the values asked for.
//
// The binary layout (VTK's vtkXMLDataParser, written by vtkXMLWriter):
// - uncompressed: one header word, the data's byte count, then the data; inline, header and
//   data are one base64 stream;
// - compressed: the header [block count, block size, last block's size (0: a full block),
//   the compressed size of each block], then the blocks one after another; inline, the
//   header and the blocks are two base64 streams (the blocks start at the next 4-character
//   group after the header's).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "ffdkit/meshio/read_limits.h"
#include "vtk_xml_tree.h"

namespace ffdkit::meshio::detail {

/// How a file's binary data are laid out: the root VTKFile's header_type, byte_order and
/// compressor attributes.
struct VtkXmlDataLayout {
  enum class Compressor { None, ZLib, LZ4, LZMA };
  std::size_t headerWordSize = 4;  ///< UInt32 (the default) or UInt64
  bool bigEndian = false;
  Compressor compressor = Compressor::None;

  /// @throws MeshIoError for an unknown header type, byte order or compressor.
  static VtkXmlDataLayout of(const VtkXmlDocument& document, const std::string& source);
};

/// What decoding the binary arrays of one read costs. `held`: the read's budget, charged with an
/// array's decoded bytes while they are converted and given them back after. `decoded`: every
/// byte decoded in the read, never given back, against the same limits: pieces whose arrays
/// alias one compressed block each count in full, so a small file cannot make the reader
/// decompress without end.
struct ArrayBudget {
  explicit ArrayBudget(ReadBudget& read) : held(read), decoded(read.limits()) {}
  ReadBudget& held;
  ReadBudget decoded;
};

/// The DataArray's first `count` values as doubles (any numeric type), each finite. The
/// returned values are the caller's to charge.
/// @throws MeshIoError naming the file, the line and the array: fewer values than `count`, an
/// unknown type, a header inconsistent with the data, a block that does not decompress, a
/// non-finite value.
std::vector<double> readRealValues(const VtkXmlDocument& document, const VtkXmlDataLayout& layout, const XmlElement& array,
                                   std::size_t count, const std::string& source, ArrayBudget& budget);

/// The DataArray's first `count` values as integers (integer types only).
std::vector<std::int64_t> readIntegerValues(const VtkXmlDocument& document, const VtkXmlDataLayout& layout, const XmlElement& array,
                                            std::size_t count, const std::string& source, ArrayBudget& budget);

}  // namespace ffdkit::meshio::detail
