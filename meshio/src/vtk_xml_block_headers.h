#pragma once
// What VTK's XML reader would allocate from a compressed data block's header, checked before
// VTK reads the file. A compressed binary DataArray starts with a header of 3 words (the block
// count, the block size, the last block's size) followed by one compressed size per block;
// vtkXMLDataParser::ReadCompressionHeader (VTK 9.1) zero-fills a vector of as many words as the
// count announces before it reads them, so the 16 bytes of a hostile header could make it
// touch gigabytes (found by fuzz_mesh_vtp: 2.06e9 blocks, an 8.2 GB fill). A real header lists
// one size per block, so its count cannot exceed the bytes that follow it; and a block
// decompresses from its compressed bytes in the file (zlib expands at most 1032:1).

#include <string>
#include <string_view>

namespace ffdkit::meshio::detail {

/// Throws MeshIoError naming the file, the line and the DataArray whose compression header
/// is inconsistent (blocks of 0 bytes, a last block larger than the others), announces more
/// blocks than the file's bytes can list, blocks larger than the file could decompress to, or
/// a block's compressed size larger than the file. Files without a compressor, ASCII arrays and headers too short to read are
/// left to VTK (which reports them as read errors).
void checkVtkXmlBlockHeaders(std::string_view bytes, const std::string& source);

}  // namespace ffdkit::meshio::detail
