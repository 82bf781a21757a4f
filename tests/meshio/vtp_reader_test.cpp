// ffdkit's VTP reader (meshio/src/vtp_format.cpp) against VTK's own writer in every layout it
// writes, checked against the mesh written and against VTK's reader of the same bytes; and on
// bad files, each refused with the file, the line and the array named.
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include "ffdkit/meshio/mesh_io.h"

namespace ffdkit::meshio {
namespace {

std::string vtpErrorOf(const std::string& bytes) {
  try {
    readMeshBytes(bytes, MeshFormat::Vtp, "test");
  } catch (const MeshIoError& e) {
    return e.what();
  }
  return "(no error)";
}

#define EXPECT_VTP_ERROR(bytes, part) EXPECT_NE(vtpErrorOf(bytes).find(part), std::string::npos) << vtpErrorOf(bytes)

// Points, and cells of every kind with what ffdkit makes of them, written out by hand.
struct Sample {
  vtkNew<vtkPolyData> poly;
  std::vector<Eigen::Vector3i> triangles;  // triangles as they are, quads as fans, the strip alternating
  std::vector<Eigen::Vector2i> segments;   // the poly-line's edges
};

void makeSample(Sample& s, bool float32) {
  const int n = 300;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-2.0, 2.0);
  vtkNew<vtkPoints> points;
  points->SetDataType(float32 ? VTK_FLOAT : VTK_DOUBLE);
  for (int i = 0; i < n; ++i) points->InsertNextPoint(coordinate(random), coordinate(random), coordinate(random));
  s.poly->SetPoints(points);
  vtkNew<vtkCellArray> polys, strips, lines, verts;
  for (vtkIdType i = 0; i + 2 < 150; i += 3) {
    const vtkIdType t[3] = {i, i + 1, i + 2};
    polys->InsertNextCell(3, t);
    s.triangles.emplace_back(int(i), int(i + 1), int(i + 2));
  }
  for (vtkIdType i = 150; i + 3 < 270; i += 4) {
    const vtkIdType q[4] = {i, i + 1, i + 2, i + 3};
    polys->InsertNextCell(4, q);
    s.triangles.emplace_back(int(i), int(i + 1), int(i + 2));
    s.triangles.emplace_back(int(i), int(i + 2), int(i + 3));
  }
  const vtkIdType strip[6] = {270, 271, 272, 273, 274, 275};
  strips->InsertNextCell(6, strip);
  for (const auto& t : {Eigen::Vector3i(270, 271, 272), Eigen::Vector3i(272, 271, 273), Eigen::Vector3i(272, 273, 274),
                        Eigen::Vector3i(274, 273, 275)})
    s.triangles.push_back(t);
  const vtkIdType line[4] = {280, 281, 282, 283};
  lines->InsertNextCell(4, line);
  s.segments = {{280, 281}, {281, 282}, {282, 283}};
  for (vtkIdType i = 290; i < 300; ++i) verts->InsertNextCell(1, &i);
  s.poly->SetPolys(polys);
  s.poly->SetStrips(strips);
  s.poly->SetLines(lines);
  s.poly->SetVerts(verts);
}

struct Layout {
  int mode;        // 0 ascii, 1 inline binary, 2 appended raw, 3 appended base64
  int compressor;  // 0 none, 1 zlib, 2 LZ4, 3 LZMA
  bool uint64Headers;
  bool bigEndian;
  std::string name() const {
    static const char* modes[] = {"ascii", "binary", "appended-raw", "appended-base64"};
    static const char* compressors[] = {"none", "zlib", "lz4", "lzma"};
    return std::string(modes[mode]) + "/" + compressors[compressor] + (uint64Headers ? "/UInt64" : "/UInt32") +
           (bigEndian ? "/BigEndian" : "/LittleEndian");
  }
};

std::string writeWithVtk(vtkPolyData* poly, const Layout& layout) {
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(poly);
  writer->WriteToOutputStringOn();
  if (layout.mode == 0) writer->SetDataModeToAscii();
  if (layout.mode == 1) writer->SetDataModeToBinary();
  if (layout.mode >= 2) {
    writer->SetDataModeToAppended();
    writer->SetEncodeAppendedData(layout.mode == 3);
  }
  if (layout.compressor == 0) writer->SetCompressorTypeToNone();
  if (layout.compressor == 1) writer->SetCompressorTypeToZLib();
  if (layout.compressor == 2) writer->SetCompressorTypeToLZ4();
  // LZMA at level 1 (VTK's default is 5): every block is compressed by an encoder of its own,
  // and at level 5 each one allocates about 90 MB and clears its match finder's tables, most of
  // this test's time under ASan (whose allocator maps every large block afresh). The reader
  // decodes an LZMA stream of any level alike.
  if (layout.compressor == 3) {
    writer->SetCompressorTypeToLZMA();
    writer->SetCompressionLevel(1);
  }
  writer->SetBlockSize(1000);  // several blocks per array, the last one partial (points: 7200 bytes in Float64)
  if (layout.uint64Headers) writer->SetHeaderTypeToUInt64();
  else writer->SetHeaderTypeToUInt32();
  if (layout.bigEndian) writer->SetByteOrderToBigEndian();
  else writer->SetByteOrderToLittleEndian();
  EXPECT_EQ(writer->Write(), 1);
  return writer->GetOutputString();
}

TEST(VtpReader, ReadsEveryLayoutVtksWriterWritesAsVtksReaderDoes) {
  int layouts = 0;
  for (bool float32 : {false, true}) {
    Sample sample;
    makeSample(sample, float32);
    for (int mode = 0; mode < 4; ++mode)
      for (int compressor = 0; compressor < 4; ++compressor)
        for (bool uint64Headers : {false, true})
          for (bool bigEndian : {false, true}) {
            if (mode == 0 && (compressor != 0 || uint64Headers || bigEndian)) continue;  // text has no binary layout
            const Layout layout{mode, compressor, uint64Headers, bigEndian};
            SCOPED_TRACE(layout.name() + (float32 ? "/Float32" : "/Float64"));
            const std::string bytes = writeWithVtk(sample.poly, layout);
            const MeshData mesh = readMeshBytes(bytes, MeshFormat::Vtp, "sample.vtp");
            ++layouts;
            // The points written, bit for bit (a Float32 file's as floats).
            ASSERT_EQ(mesh.points.rows(), 300);
            for (int i = 0; i < 300; ++i) {
              double p[3];
              sample.poly->GetPoint(i, p);
              ASSERT_EQ(mesh.points.row(i), Eigen::RowVector3d(p[0], p[1], p[2])) << "point " << i;
            }
            // And what VTK's reader makes of the same bytes (a valid file).
            vtkNew<vtkXMLPolyDataReader> vtkReader;
            vtkReader->ReadFromInputStringOn();
            vtkReader->SetInputString(bytes);
            vtkReader->Update();
            ASSERT_EQ(vtkReader->GetOutput()->GetNumberOfPoints(), 300);
            for (int i = 0; i < 300; ++i) {
              double p[3];
              vtkReader->GetOutput()->GetPoint(i, p);
              ASSERT_EQ(mesh.points.row(i), Eigen::RowVector3d(p[0], p[1], p[2])) << "point " << i << " as VTK reads it";
            }
            ASSERT_EQ(std::size_t(mesh.triangles.rows()), sample.triangles.size());
            for (std::size_t t = 0; t < sample.triangles.size(); ++t)
              ASSERT_EQ(mesh.triangles.row(Eigen::Index(t)), sample.triangles[t].transpose()) << "triangle " << t;
            ASSERT_EQ(std::size_t(mesh.segments.rows()), sample.segments.size());
            for (std::size_t e = 0; e < sample.segments.size(); ++e)
              ASSERT_EQ(mesh.segments.row(Eigen::Index(e)), sample.segments[e].transpose()) << "segment " << e;
            EXPECT_FALSE(mesh.hasNormals);
          }
  }
  EXPECT_EQ(layouts, 2 * (1 + 3 * 4 * 2 * 2));
}

// A file of two pieces (ParaView writes one per process): the second piece's ids count from
// its own first point.
TEST(VtpReader, JoinsPiecesShiftingEachPiecesPointIds) {
  const std::string piece = R"(<Piece NumberOfPoints="3" NumberOfPolys="1">
  <Points><DataArray type="Float32" NumberOfComponents="3" format="ascii">0 0 0  1 0 0  0 1 %</DataArray></Points>
  <Polys><DataArray type="Int32" Name="connectivity" format="ascii">0 1 2</DataArray>
         <DataArray type="Int32" Name="offsets" format="ascii">3</DataArray></Polys>
</Piece>
)";
  std::string first = piece, second = piece;
  first.replace(first.find('%'), 1, "0");
  second.replace(second.find('%'), 1, "5");
  const MeshData mesh =
      readMeshBytes("<?xml version=\"1.0\"?>\n<!-- two pieces -->\n<VTKFile type=\"PolyData\" version=\"1.0\">\n<PolyData>\n" + first +
                        second + "</PolyData>\n</VTKFile>\n",
                    MeshFormat::Vtp, "two.vtp");
  ASSERT_EQ(mesh.points.rows(), 6);
  EXPECT_EQ(mesh.points.row(5), Eigen::RowVector3d(0, 1, 5));
  ASSERT_EQ(mesh.triangles.rows(), 2);
  EXPECT_EQ(mesh.triangles.row(1), Eigen::RowVector3i(3, 4, 5));
}

// A one-piece file around `arrays` (inside <Points>) or `body` (the rest of the piece).
std::string vtp(const std::string& rootAttributes, const std::string& points, const std::string& body = "",
                const std::string& appended = "", const std::string& pieceAttributes = "NumberOfPoints=\"3\" NumberOfPolys=\"0\"") {
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" " + rootAttributes + ">\n<PolyData>\n<Piece " +
         pieceAttributes + ">\n<Points>\n" + points + "\n</Points>\n" + body + "</Piece>\n</PolyData>\n" + appended + "</VTKFile>\n";
}

const char* kZlib32 = "byte_order=\"LittleEndian\" header_type=\"UInt32\" compressor=\"vtkZLibDataCompressor\"";
const std::string kTriangle = "<DataArray type=\"Float64\" Name=\"P\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0</DataArray>";

// Compression headers announce sizes; each is checked against the bytes there before anything
// is allocated for it (VTK's reader zero-filled 8.2 GB for a 16-byte header, divided by a
// block size of 0, and wrote 312 bytes into a 1-byte array: fuzz_mesh_vtp).
TEST(VtpReader, ChecksCompressionHeadersAgainstTheFileBeforeAllocating) {
  // 0x7fffffff blocks of 32768 bytes, little-endian UInt32 words, base64.
  EXPECT_VTP_ERROR(vtp(kZlib32, "<DataArray type=\"Float32\" Name=\"Points\" NumberOfComponents=\"3\" format=\"binary\">\n"
                                "////fwCAAAAAAAAA</DataArray>"),
                   "test:6: DataArray \"Points\": its compression header announces 2147483647 blocks, more than a file of");
  // 2^40 blocks, big-endian UInt64 words, base64.
  EXPECT_VTP_ERROR(vtp("byte_order=\"BigEndian\" header_type=\"UInt64\" compressor=\"vtkLZ4DataCompressor\"",
                       "<DataArray type=\"Float32\" Name=\"P\" NumberOfComponents=\"3\" format=\"binary\">"
                       "AAABAAAAAAAAAAAAAACAAAAAAAAAAAAA</DataArray>"),
                   "its compression header announces 1099511627776 blocks");
  // One block of 2^31 bytes from a file of a few hundred.
  EXPECT_VTP_ERROR(vtp(kZlib32, "<DataArray type=\"Float32\" Name=\"P\" NumberOfComponents=\"3\" format=\"binary\">"
                                "AQAAAAAAAIAAAAAA</DataArray>"),
                   "announces blocks of 2147483648 bytes");
  // Appended raw data: the header at the array's offset after the '_'.
  std::string raw(24, '\0');
  raw[5] = 1;           // little-endian UInt64 word 0 = 2^40 blocks
  raw[9] = char(0x80);  // word 1 = 32768
  const std::string appended = vtp("byte_order=\"LittleEndian\" header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\"",
                                   "<DataArray type=\"Float32\" Name=\"P\" NumberOfComponents=\"3\" format=\"appended\" offset=\"4\"/>",
                                   "", "<AppendedData encoding=\"raw\">\n_" + std::string(4, 'x') + raw + "\n</AppendedData>\n");
  EXPECT_VTP_ERROR(appended, "its compression header announces 1099511627776 blocks");
  // One block of 36 bytes whose compressed size (the next word) is more than the file holds.
  std::string oneBlock = appended;
  const std::size_t header = oneBlock.find("\n_") + 6;  // after the '_' and the 4 bytes before the offset
  oneBlock[header + 5] = 0;
  oneBlock[header] = 1;
  oneBlock[header + 9] = 0, oneBlock[header + 8] = 36;
  oneBlock.insert(header + 24, std::string("\xff\xff\xff\xff\xff\x00\x00\x00", 8));
  EXPECT_VTP_ERROR(oneBlock, "DataArray \"P\": block 0 announces 1099511627775 compressed bytes, more than the");
  // A block size in a padded last base64 group ("mat=" gives 2 bytes), as VTK reads it.
  EXPECT_VTP_ERROR(vtp(kZlib32, "<DataArray type=\"Float32\" Name=\"P\" NumberOfComponents=\"3\" format=\"binary\">"
                                "AQAAAACAAADAAAAAXgArmat=</DataArray>"),
                   "block 0 announces 2569732190 compressed bytes");
  // Inconsistent headers (1 block of 0 bytes, the last of 192; 1 block of 32768, the last of
  // 65536; no blocks, a last of 192).
  for (const char* bad : {"AQAAAAAAAADAAAAA", "AQAAAACAAAAAAAEA", "AAAAAACAAADAAAAA"})
    EXPECT_VTP_ERROR(vtp(kZlib32, std::string("<DataArray type=\"Float32\" Name=\"P\" NumberOfComponents=\"3\" format=\"binary\">") +
                                      bad + "AAAAAA==</DataArray>"),
                     "DataArray \"P\": its compression header is inconsistent");
  // A header cut short.
  EXPECT_VTP_ERROR(vtp(kZlib32, "<DataArray type=\"Float32\" Name=\"P\" NumberOfComponents=\"3\" format=\"binary\">AQAA</DataArray>"),
                   "test:6: DataArray \"P\": the data end inside its compression header");
  // Fewer bytes than the points need: 1 block of 12 bytes for 3 points of 12 bytes each.
  EXPECT_VTP_ERROR(vtp(kZlib32, "<DataArray type=\"Float32\" Name=\"P\" NumberOfComponents=\"3\" format=\"binary\">"
                                "AQAAAAwAAAAMAAAAFAAAAA==eJxjYGBgAAAABAAB</DataArray>"),
                   "DataArray \"P\": decompresses to 12 bytes, 36 needed");
}

TEST(VtpReader, RefusesBlocksThatDoNotDecompressToTheirSize) {
  // A real zlib file from VTK's writer, one byte of a compressed block flipped.
  Sample sample;
  makeSample(sample, false);
  std::string bytes = writeWithVtk(sample.poly, Layout{2, 1, false, false});
  const std::size_t data = bytes.find("\n   _") + 5;
  bytes[data + 80] = char(bytes[data + 80] ^ 0x5a);  // past the points' header of 11 words: inside block 0
  EXPECT_VTP_ERROR(bytes, "test:9: DataArray \"Points\": block 0 does not decompress to its 1000 bytes");
  // The same file cut inside its appended data.
  std::string cut = writeWithVtk(sample.poly, Layout{2, 2, false, false});
  cut.erase(cut.find("\n   _") + 300, cut.rfind("\n  </AppendedData>") - cut.find("\n   _") - 300);
  EXPECT_NE(vtpErrorOf(cut).find("test:"), std::string::npos) << vtpErrorOf(cut);
}

TEST(VtpReader, ChecksCellsAndPoints) {
  const auto polys = [](const char* connectivity, const char* offsets) {
    return std::string("<Polys><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">") + connectivity +
           "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">" + offsets + "</DataArray></Polys>\n";
  };
  const std::string oneTriangle = "NumberOfPoints=\"3\" NumberOfPolys=\"1\"";
  EXPECT_EQ(readMeshBytes(vtp("", kTriangle, polys("0 1 2", "3"), "", oneTriangle), MeshFormat::Vtp, "t").triangles.rows(), 1);
  EXPECT_VTP_ERROR(vtp("", kTriangle, polys("0 1 7", "3"), "", oneTriangle), "test:8: polygon 0: point id 7 is outside 0..2");
  EXPECT_VTP_ERROR(vtp("", kTriangle, polys("0 1 -1", "3"), "", oneTriangle), "polygon 0: point id -1 is outside 0..2");
  EXPECT_VTP_ERROR(vtp("", kTriangle, polys("0 1", "3"), "", oneTriangle), "DataArray \"connectivity\": 3 values needed, more than its 3 characters can hold");
  EXPECT_VTP_ERROR(vtp("", kTriangle, polys("0 1            ", "3"), "", oneTriangle), "DataArray \"connectivity\": holds 2 values, 3 needed");
  EXPECT_VTP_ERROR(vtp("", kTriangle, polys("0 1 2 0 1 2", "6 3"), "", "NumberOfPoints=\"3\" NumberOfPolys=\"2\""),
                   "polygon 1: offset 3 is before the previous 6");
  EXPECT_VTP_ERROR(vtp("", kTriangle, polys("0 1 2", "9223372036854775807"), "", oneTriangle),
                   "test:8: Polys connectivity: 9223372036854775807 items of 8 bytes need 16.0 EiB; with what this read holds "
                   "already (80 bytes) that is over the read limit of 4.0 GiB (--max-memory)");
  EXPECT_VTP_ERROR(vtp("", kTriangle, polys("0 x 2", "3"), "", oneTriangle), "value 1: expected a number, got 'x'");
  EXPECT_VTP_ERROR(vtp("", kTriangle, "", "", oneTriangle), "Piece: 1 polygon cells but no <Polys>");
  // Points: finite, three components, present.
  EXPECT_VTP_ERROR(vtp("", "<DataArray type=\"Float64\" Name=\"P\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 nan 0 0 1 0</DataArray>"),
                   "test:6: DataArray \"P\": value 4 is not finite");
  EXPECT_VTP_ERROR(vtp("", "<DataArray type=\"Float64\" Name=\"P\" NumberOfComponents=\"2\" format=\"ascii\">0 0 0 1 0 0</DataArray>"),
                   "points need NumberOfComponents=\"3\"");
  EXPECT_VTP_ERROR(vtp("", "<DataArray type=\"Float128\" Name=\"P\" NumberOfComponents=\"3\" format=\"ascii\">0</DataArray>"),
                   "unknown type \"Float128\"");
  // A binary infinity, uncompressed: header 36, then 9 doubles.
  std::string raw(4 + 72, '\0');
  raw[0] = 72;
  const double inf = std::numeric_limits<double>::infinity();
  std::memcpy(raw.data() + 4 + 8 * 7, &inf, 8);
  EXPECT_VTP_ERROR(vtp("byte_order=\"LittleEndian\"",
                       "<DataArray type=\"Float64\" Name=\"P\" NumberOfComponents=\"3\" format=\"appended\" offset=\"0\"/>", "",
                       "<AppendedData encoding=\"raw\">_" + raw + "</AppendedData>\n"),
                   "DataArray \"P\": value 7 is not finite");
  // Counts no file of this size can back.
  EXPECT_VTP_ERROR(vtp("", kTriangle, "", "", "NumberOfPoints=\"99999999999\""), "NumberOfPoints announces 99999999999, more than a file of");
  EXPECT_VTP_ERROR(vtp("byte_order=\"LittleEndian\"",
                       "<DataArray type=\"Float64\" Name=\"P\" NumberOfComponents=\"3\" format=\"appended\" offset=\"0\"/>", "",
                       "<AppendedData encoding=\"raw\">_" + raw + "</AppendedData>\n", "NumberOfPoints=\"1000000\""),
                   "DataArray \"P\": holds 72 bytes, 24000000 needed");
}

TEST(VtpReader, RefusesMalformedXml) {
  EXPECT_VTP_ERROR("<VTKFile type=\"PolyData\"", "test:1: the tag <VTKFile is not closed");
  EXPECT_VTP_ERROR("<VTKFile type=\"PolyData\"><PolyData></Piece></VTKFile>", "test:1: </Piece> does not close <PolyData>");
  EXPECT_VTP_ERROR("<VTKFile type=\"PolyData\" version=1.0></VTKFile>", "attribute version's value is not quoted");
  EXPECT_VTP_ERROR("<VTKFile type=\"UnstructuredGrid\"></VTKFile>", "a VTK UnstructuredGrid file, not PolyData");
  EXPECT_VTP_ERROR("<!DOCTYPE x><VTKFile/>", "DOCTYPE and CDATA sections are not part of VTK's XML files");
  EXPECT_VTP_ERROR("<Other/>", "the root element is <Other>, not <VTKFile>");
  EXPECT_VTP_ERROR(vtp("compressor=\"vtkBZip2\"", kTriangle), "unknown compressor \"vtkBZip2\"");
  std::string deep = "<VTKFile type=\"PolyData\">";
  for (int i = 0; i < 100000; ++i) deep += "<a>";  // no recursion: the depth is refused, not the stack
  EXPECT_VTP_ERROR(deep, "elements nest deeper than 32");
  EXPECT_VTP_ERROR(vtp("", "<DataArray type=\"Float64\" Name=\"P\" NumberOfComponents=\"3\" format=\"appended\" offset=\"0\"/>", "",
                       "<AppendedData encoding=\"raw\">\n</AppendedData>\n"),
                   "<AppendedData>: its data do not start with '_'");
  EXPECT_VTP_ERROR(vtp("", "<DataArray type=\"Float64\" Name=\"P\" NumberOfComponents=\"3\" format=\"appended\" offset=\"99\"/>", "",
                       "<AppendedData encoding=\"raw\">_abc</AppendedData>\n"),
                   "DataArray \"P\": its offset 99 is past the 3 bytes of appended data");
}

// The inputs that crashed VTK's reader or made it allocate gigabytes (found by fuzz_mesh_vtp):
// each is an error naming the file, or a mesh whose every index and point checks (one has a
// broken Normals array, which ffdkit does not read). The fuzz corpus tests run them too.
TEST(VtpReader, TheFuzzFindingsThatBrokeVtksReaderAreErrorsOrCheckedMeshes) {
  const std::filesystem::path dir = std::filesystem::path(FFDKIT_SOURCE_DIR) / "tests/fuzz/regressions/fuzz_mesh_vtp";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    std::ifstream in(entry.path(), std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    const std::string name = entry.path().filename().string();
    SCOPED_TRACE(name);
    ++files;
    try {
      const MeshData mesh = readMeshBytes(bytes.str(), MeshFormat::Vtp, name);
      EXPECT_NO_THROW(validateMesh(mesh, name));
    } catch (const MeshIoError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(name + ":", 0), 0u) << e.what();
    }
  }
  EXPECT_GE(files, 6);
  // The 312-byte overflow: 13 polygons whose offsets ask for more of the connectivity than its
  // block holds.
  std::ifstream in(dir / "crash-a9eb95eb5d405c888c4370041e6143e8c156488b", std::ios::binary);
  std::stringstream overflow;
  overflow << in.rdbuf();
  EXPECT_NE(vtpErrorOf(overflow.str()), "(no error)");
}

}  // namespace
}  // namespace ffdkit::meshio
