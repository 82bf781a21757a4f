// Fuzz target: a mesh read, checked, written in every writable format, read back and compared.
// The first byte picks the format of the rest (MeshFormat, modulo the nine formats). A mesh that
// reads is checked here by rules written independently of meshio's validateMesh; then each
// writer writes it and the matching reader reads those bytes back. What each format keeps:
//   OBJ, PLY ASCII   points bit for bit (shortest round-trip text), triangles, segments, normals
//   PLY binary LE/BE points rounded to float32, triangles, segments, normals
//   STL (binary)     triangles only: each corner's point rounded to float32 (identical corners
//                    merged into one point, so indices and unused points are not kept)
//   XYZ              points bit for bit; no cells, no normals
//   NPY              points bit for bit (float64); no cells, no normals
//   VTP, VTK         points bit for bit (Float64), triangles, segments, normals
// ("normals": the flag that the file has normals; writers recompute them from the points, and
// only for a mesh with triangles.) A writer may refuse a mesh its format cannot hold with a
// MeshIoError (STL without triangles); bytes a writer produced that its reader refuses, or that
// read back as a different mesh, are findings, as is any other exception or a sanitizer report.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "ffdkit/meshio/mesh_io.h"

namespace {

using ffdkit::meshio::MeshData;
using ffdkit::meshio::MeshFormat;
using ffdkit::meshio::MeshIoError;
using ffdkit::meshio::PlyEncoding;

constexpr MeshFormat kInputFormats[] = {MeshFormat::Obj, MeshFormat::Ply,  MeshFormat::Stl,
                                        MeshFormat::Xyz, MeshFormat::Npy,  MeshFormat::Gltf,
                                        MeshFormat::Glb, MeshFormat::Vtp,  MeshFormat::Vtk};

// A read small enough for tens of thousands of executions per second: a fuzz input is at most
// 64 KiB, and what it may make a reader allocate stays within a few MiB.
ffdkit::meshio::MeshReadOptions smallRead() {
  ffdkit::meshio::MeshReadOptions options;
  options.limits.maxPoints = 100'000;
  options.limits.maxMemoryBytes = 32u << 20;
  return options;
}

enum class PointsKept { Exact, Float32, Float32TriangleCorners };

struct Written {
  const char* name;
  MeshFormat format;
  PlyEncoding plyEncoding = PlyEncoding::BinaryLittleEndian;
  PointsKept points = PointsKept::Exact;
  bool cells = true;  // triangles and segments, in order
  bool normals = true;
};

constexpr Written kWritten[] = {
    {"obj", MeshFormat::Obj},
    {"ply ascii", MeshFormat::Ply, PlyEncoding::Ascii},
    {"ply binary le", MeshFormat::Ply, PlyEncoding::BinaryLittleEndian, PointsKept::Float32},
    {"ply binary be", MeshFormat::Ply, PlyEncoding::BinaryBigEndian, PointsKept::Float32},
    {"stl", MeshFormat::Stl, PlyEncoding::BinaryLittleEndian, PointsKept::Float32TriangleCorners, false, false},
    {"xyz", MeshFormat::Xyz, PlyEncoding::BinaryLittleEndian, PointsKept::Exact, false, false},
    {"npy", MeshFormat::Npy, PlyEncoding::BinaryLittleEndian, PointsKept::Exact, false, false},
    {"vtp", MeshFormat::Vtp},
    {"vtk", MeshFormat::Vtk},
};

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "mesh round trip: %s\n", what.c_str());
  std::abort();
}

// The rules a read mesh must meet, written here rather than taken from validateMesh.
void checkMesh(const MeshData& mesh, const std::string& what) {
  const Eigen::Index n = mesh.points.rows();
  if (n <= 0) finding(what + ": no points");
  if (mesh.points.cols() != 3 || mesh.triangles.cols() != 3 || mesh.segments.cols() != 2) finding(what + ": bad shapes");
  for (Eigen::Index i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(mesh.points(i, c))) finding(what + ": point " + std::to_string(i) + " is not finite");
  auto inRange = [&](const auto& cells, const char* kind) {
    for (Eigen::Index r = 0; r < cells.rows(); ++r)
      for (Eigen::Index c = 0; c < cells.cols(); ++c)
        if (cells(r, c) < 0 || cells(r, c) >= n)
          finding(what + ": " + kind + " " + std::to_string(r) + " has index " + std::to_string(cells(r, c)) +
                  " of " + std::to_string(n) + " points");
  };
  inRange(mesh.triangles, "triangle");
  inRange(mesh.segments, "segment");
}

double expected(double value, bool float32) { return float32 ? double(float(value)) : value; }

bool same(double got, double want, bool float32) {
  // Double formats: the same bits. Float formats: the float32 value (a merged STL corner may
  // come from +0 or -0, which are equal as values).
  return float32 ? got == want : std::bit_cast<std::uint64_t>(got) == std::bit_cast<std::uint64_t>(want);
}

void compare(const MeshData& original, const MeshData& back, const Written& written) {
  const std::string what = std::string("written as ") + written.name + " and read back";
  checkMesh(back, what);
  const bool float32 = written.points != PointsKept::Exact;
  if (written.points == PointsKept::Float32TriangleCorners) {
    if (back.triangles.rows() != original.triangles.rows())
      finding(what + ": " + std::to_string(back.triangles.rows()) + " triangles, expected " +
              std::to_string(original.triangles.rows()));
    for (Eigen::Index t = 0; t < original.triangles.rows(); ++t)
      for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c) {
          const double want = expected(original.points(original.triangles(t, k), c), float32);
          const double got = back.points(back.triangles(t, k), c);
          if (!same(got, want, float32))
            finding(what + ": triangle " + std::to_string(t) + " corner " + std::to_string(k) + " coordinate " +
                    std::to_string(c) + " is " + std::to_string(got) + ", expected " + std::to_string(want));
        }
    if (back.segments.rows() != 0) finding(what + ": segments appeared");
    return;
  }
  if (back.points.rows() != original.points.rows())
    finding(what + ": " + std::to_string(back.points.rows()) + " points, expected " + std::to_string(original.points.rows()));
  for (Eigen::Index i = 0; i < original.points.rows(); ++i)
    for (int c = 0; c < 3; ++c)
      if (!same(back.points(i, c), expected(original.points(i, c), float32), float32))
        finding(what + ": point " + std::to_string(i) + " coordinate " + std::to_string(c) + " changed");
  if (written.cells) {
    if (back.triangles != original.triangles) finding(what + ": the triangles changed");
    if (back.segments != original.segments) finding(what + ": the segments changed");
  } else if (back.triangles.rows() != 0 || back.segments.rows() != 0) {
    finding(what + ": cells appeared");
  }
  const bool normals = written.normals && original.hasNormals && original.triangles.rows() > 0;
  if (back.hasNormals != normals) finding(what + ": has normals " + std::to_string(back.hasNormals) + ", expected " + std::to_string(normals));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const MeshFormat input = kInputFormats[data[0] % std::size(kInputFormats)];
  const std::string_view bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  MeshData mesh;
  try {
    mesh = ffdkit::meshio::readMeshBytes(bytes, input, "fuzz", smallRead());
  } catch (const MeshIoError&) {
    return 0;
  }
  checkMesh(mesh, "the read mesh");
  for (const Written& written : kWritten) {
    std::string file;
    try {
      ffdkit::meshio::MeshWriteOptions options;
      options.plyEncoding = written.plyEncoding;
      file = ffdkit::meshio::meshFileBytes(mesh, written.format, options);
    } catch (const MeshIoError&) {
      continue;  // a mesh this format cannot hold
    }
    MeshData back;
    try {
      // The default budget: an STL read back holds three points per triangle, more than the
      // small read allowed; what was written is bounded by what was read.
      back = ffdkit::meshio::readMeshBytes(file, written.format, "fuzz-written");
    } catch (const MeshIoError& e) {
      finding(std::string("written as ") + written.name + ", not read back: " + e.what());
    }
    compare(mesh, back, written);
  }
  return 0;
}
