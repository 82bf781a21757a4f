#pragma once
// The bad mesh files of issue 17's table, built byte by byte (independent of ffdkit's writers),
// shared by the reader tests and the CLI tests. Each comes with the text its error must contain.

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace ffdkit::meshio::test {

struct HostileFile {
  std::string name;      ///< file name (its extension picks the reader)
  std::string bytes;
  std::string expected;  ///< part of the error message
};

template <class T>
void appendLittleEndian(std::string& out, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));  // the test machines are little-endian (x86-64)
  out.append(raw, sizeof(T));
}

/// A binary little-endian PLY header for `vertices` float xyz vertices and `faces` faces.
inline std::string plyHeader(const std::string& vertices, const std::string& faces) {
  return "ply\nformat binary_little_endian 1.0\nelement vertex " + vertices +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " + faces +
         "\nproperty list uchar int vertex_indices\nend_header\n";
}

inline std::string threeVertices() {
  std::string out;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) appendLittleEndian(out, v);
  return out;
}

inline std::vector<HostileFile> hostileFiles() {
  std::vector<HostileFile> files;
  {
    std::string b = plyHeader("3", "1") + threeVertices();
    b += char(3);
    for (std::int32_t i : {0, 1, 99999}) appendLittleEndian(b, i);
    files.push_back({"face-index.ply", b, "face 0: vertex index 99999 is outside 0..2"});
  }
  {
    std::string b = plyHeader("3", "1") + threeVertices();
    b += char(255);
    appendLittleEndian(b, std::int32_t(0));
    files.push_back({"list-past-end.ply", b, "face 0 (vertex_indices): a list of 255 values runs past the end of the file"});
  }
  files.push_back({"million-no-data.ply", plyHeader("1000000", "0"),
                   "element 'vertex' announces 1000000 items of at least 12 bytes, the file has 0 bytes of data left"});
  files.push_back({"four-billion.ply", plyHeader("4000000000", "0") + threeVertices(),
                   "element 'vertex' announces 4000000000 items"});
  files.push_back({"accessor.gltf",
                   R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3000, "type": "VEC3"}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]}
)",
                   "3000 elements of 12 bytes from offset 0 run past buffer view 0 of 36 bytes"});
  files.push_back({"face-index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 100000\n",
                   "face-index.obj:4: face 0: vertex index 100000 is outside 1..3"});
  files.push_back({"nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "nan.obj:2: vertex 1: non-finite number 'nan'"});
  files.push_back({"inf.obj", "v 0 0 0\nv 1 0 0\nv inf 0 0\nf 1 2 3\n", "inf.obj:3: vertex 2: non-finite number 'inf'"});
  {
    std::string b(80, ' ');
    appendLittleEndian(b, std::uint32_t(1000000));
    b.append(100, '\0');
    files.push_back({"short.stl", b, "announces 1000000 triangles (50000084 bytes), the file has 184 bytes"});
  }
  return files;
}

// Issue 32's files (hostile_round3_test.cpp): each built byte by byte, independent of ffdkit's
// writers.

/// A binary PLY of three float vertices whose vertex element declares `properties` (in order,
/// each a float), one record of three floats per vertex, and nothing else.
inline std::string plyWithVertexProperties(const std::vector<std::string>& properties) {
  std::string b = "ply\nformat binary_little_endian 1.0\nelement vertex 3\n";
  for (const std::string& p : properties) b += "property float " + p + "\n";
  b += "end_header\n";
  for (int v = 0; v < 3; ++v)
    for (std::size_t p = 0; p < properties.size(); ++p) appendLittleEndian(b, float(v + 1) * 10.0f + float(p));
  return b;
}

/// The issue's first file: "x" declared twice, "z" not at all.
inline std::string duplicateCoordinatePly() { return plyWithVertexProperties({"x", "x", "y"}); }

/// An ASCII PLY of 4 vertices with two `face` elements of one triangle each.
inline std::string twoFaceElementsPly() {
  return "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nelement face 1\nproperty list uchar int vertex_indices\n"
         "end_header\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n";
}

/// An ASCII PLY of 3 vertices whose `edge` element has `vertex1` but no `vertex2`.
inline std::string edgeWithoutVertex2Ply() {
  return "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element edge 2\nproperty int vertex1\nproperty uchar red\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 255\n1 255\n";
}

/// A glTF whose one accessor of `points` points is used by each of `primitives` primitives of
/// one mesh, instanced by `nodes` nodes, each translated by (node index, 0, 0): it describes
/// points * primitives * nodes points in a file of about 16 * points + 31 * primitives +
/// 30 * nodes bytes. The accessor's points are (k, 0, 0), k = 0..points-1.
inline std::string instancedGltf(int points, int primitives, int nodes) {
  static constexpr char kBase64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string raw;
  for (int k = 0; k < points; ++k)
    for (float v : {float(k), 0.0f, 0.0f}) appendLittleEndian(raw, v);
  std::string data;
  for (std::size_t i = 0; i < raw.size(); i += 3) {
    const auto byte = [&](std::size_t k) { return k < raw.size() ? static_cast<unsigned char>(raw[k]) : 0u; };
    const std::uint32_t group = byte(i) << 16 | byte(i + 1) << 8 | byte(i + 2);
    data += kBase64[group >> 18 & 63];
    data += kBase64[group >> 12 & 63];
    data += i + 1 < raw.size() ? kBase64[group >> 6 & 63] : '=';
    data += i + 2 < raw.size() ? kBase64[group & 63] : '=';
  }
  std::string json = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [)";
  for (int n = 0; n < nodes; ++n) json.append(n > 0 ? "," : "").append(std::to_string(n));
  json += "]}], \"nodes\": [";
  for (int n = 0; n < nodes; ++n)
    json.append(n > 0 ? "," : "").append("{\"mesh\":0,\"translation\":[").append(std::to_string(n)).append(",0,0]}");
  json += "], \"meshes\": [{\"primitives\": [";
  for (int p = 0; p < primitives; ++p) json.append(p > 0 ? "," : "").append("{\"attributes\":{\"POSITION\":0},\"mode\":0}");
  json += "]}], \"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": " + std::to_string(points) +
          ", \"type\": \"VEC3\"}], \"bufferViews\": [{\"buffer\": 0, \"byteLength\": " + std::to_string(raw.size()) +
          "}], \"buffers\": [{\"byteLength\": " + std::to_string(raw.size()) +
          ", \"uri\": \"data:application/octet-stream;base64," + data + "\"}]}\n";
  return json;
}

/// A VTP of `pieces` pieces, each of three ASCII points and one vertex cell whose Int64
/// connectivity is the appended zlib data at offset 0: the same compressed block for every
/// piece. `block` is a whole compression header and its blocks (vtkZLibDataCompressor, UInt32
/// header words) of `ids` zero ids.
inline std::string aliasedBlockVtp(int pieces, const std::string& block, std::uint64_t ids) {
  std::string b = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
                  "header_type=\"UInt32\" compressor=\"vtkZLibDataCompressor\">\n<PolyData>\n";
  for (int p = 0; p < pieces; ++p)
    b += "<Piece NumberOfPoints=\"3\" NumberOfVerts=\"1\">\n<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" "
         "format=\"ascii\">0 0 0 1 0 0 0 1 0</DataArray></Points>\n<Verts>"
         "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"appended\" offset=\"0\"/>"
         "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">" + std::to_string(ids) + "</DataArray></Verts>\n</Piece>\n";
  b += "</PolyData>\n<AppendedData encoding=\"raw\">\n_" + block + "\n</AppendedData>\n</VTKFile>\n";
  return b;
}

}  // namespace ffdkit::meshio::test
