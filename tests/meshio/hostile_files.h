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

}  // namespace ffdkit::meshio::test
