// Reading and writing mesh files per format and size (the CLI's read and write steps):
//   BM_ReadMesh/format:ply/vertices:1000000   a 1000 x 1000 grid, 1,996,002 triangles (binary PLY: 38 MB)
//   BM_WriteMesh/format:xyz/vertices:1000000  points only (a durable write: fsync before rename)
//   BM_EncodeMesh/format:xyz/...              the file's bytes only (no file)
// Each run first checks that the file read back has the mesh's counts (the correctness check
// beside the timing). Files go to the system temp folder.
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <unistd.h>

#include "ffdkit/meshio/mesh_io.h"

namespace {

using namespace ffdkit::meshio;
namespace fs = std::filesystem;

// A side x side grid of points on a gently curved sheet, two triangles per square.
MeshData grid(int side, bool triangles) {
  MeshData mesh;
  mesh.points.resize(Eigen::Index(side) * side, 3);
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      const double x = double(i) / side, y = double(j) / side;
      mesh.points.row(Eigen::Index(j) * side + i) << x, y, 0.1 * x * x - 0.05 * y + 1e-3 * std::sin(37.0 * x * y);
    }
  if (!triangles) return mesh;
  mesh.triangles.resize(2 * Eigen::Index(side - 1) * (side - 1), 3);
  Eigen::Index t = 0;
  for (int j = 0; j + 1 < side; ++j)
    for (int i = 0; i + 1 < side; ++i) {
      const int a = j * side + i, b = a + 1, c = a + side, d = c + 1;
      mesh.triangles.row(t++) << a, b, d;
      mesh.triangles.row(t++) << a, d, c;
    }
  return mesh;
}

fs::path benchFile(const std::string& ext, int side) {
  return fs::temp_directory_path() / ("ffdkit-bench-meshio-" + std::to_string(::getpid()) + "-" + std::to_string(side) + ext);
}

// Every format keeps the counts (STL merges its corners back into the grid's points); float
// formats keep the points to float precision.
void check(const MeshData& read, const MeshData& mesh) {
  if (read.points.rows() != mesh.points.rows() || read.triangles.rows() != mesh.triangles.rows())
    throw std::runtime_error("read back a different mesh: " + std::to_string(read.points.rows()) + " points");
  if (read.triangles.rows() == 0 && (read.points - mesh.points).cwiseAbs().maxCoeff() > 1e-6)
    throw std::runtime_error("read back different points");
}

void BM_ReadMesh(benchmark::State& state, const std::string& ext, bool triangles) {
  const int side = int(std::lround(std::sqrt(double(state.range(0)))));
  const MeshData mesh = grid(side, triangles);
  const fs::path path = benchFile(ext, side);
  writeMesh(path, mesh);
  check(readMesh(path), mesh);
  for (auto _ : state) benchmark::DoNotOptimize(readMesh(path));
  state.counters["MB"] = double(fs::file_size(path)) / 1e6;
  fs::remove(path);
}

void BM_WriteMesh(benchmark::State& state, const std::string& ext, bool triangles) {
  const int side = int(std::lround(std::sqrt(double(state.range(0)))));
  const MeshData mesh = grid(side, triangles);
  const fs::path path = benchFile(ext, side);
  writeMesh(path, mesh);
  check(readMesh(path), mesh);
  for (auto _ : state) writeMesh(path, mesh);
  state.counters["MB"] = double(fs::file_size(path)) / 1e6;
  fs::remove(path);
}

// The file's bytes only, no file: BM_WriteMesh minus the durable write (fsync), which on this
// machine's disk is most of a binary write.
void BM_EncodeMesh(benchmark::State& state, const std::string& ext, bool triangles) {
  const int side = int(std::lround(std::sqrt(double(state.range(0)))));
  const MeshData mesh = grid(side, triangles);
  const MeshFormat format = *meshFormatOf(fs::path("mesh" + ext));
  std::size_t bytes = 0;
  for (auto _ : state) bytes = meshFileBytes(mesh, format, {}).size();
  state.counters["MB"] = double(bytes) / 1e6;
}

void sizes(benchmark::internal::Benchmark* b) {
  b->ArgName("vertices")->Arg(10000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();
}

#define FFDKIT_MESH_BENCH(name, ext, triangles)                                                   \
  BENCHMARK_CAPTURE(BM_ReadMesh, format:name, std::string(ext), triangles)->Apply(sizes);         \
  BENCHMARK_CAPTURE(BM_WriteMesh, format:name, std::string(ext), triangles)->Apply(sizes);       \
  BENCHMARK_CAPTURE(BM_EncodeMesh, format:name, std::string(ext), triangles)->Apply(sizes)

FFDKIT_MESH_BENCH(ply, ".ply", true);
FFDKIT_MESH_BENCH(obj, ".obj", true);
FFDKIT_MESH_BENCH(stl, ".stl", true);
FFDKIT_MESH_BENCH(vtp, ".vtp", true);
FFDKIT_MESH_BENCH(xyz, ".xyz", false);
FFDKIT_MESH_BENCH(npy, ".npy", false);

}  // namespace
