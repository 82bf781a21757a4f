// A Gmsh MSH 4.1 binary file read and written back (meshio/gmsh.h), by node count:
//   BM_GmshRead/nodes:1000000    read and validate the file (nodes, hexahedra, tags), from disk
//   BM_GmshWrite/nodes:1000000   write it with moved nodes (pass-through, not flushed to disk)
//   BM_GmshCheck/nodes:1000000   the cell check of the hexahedra (meshio/element_cells.h)
// The file is a unit cube of n^3 nodes and (n-1)^3 hexahedra in one volume entity, with a
// physical name, made here value by value as gmsh writes it (so that the benchmark needs no
// gmsh). Each size is first checked: the cells are valid, their volumes add up to 1, and the
// written file reads back with the moved nodes and the same bytes from $Elements on.
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>

#include "ffdkit/meshio/gmsh.h"

namespace {

using namespace ffdkit;
namespace fs = std::filesystem;

template <class T>
void put(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

std::string cubeMsh(int n) {
  const std::uint64_t nodes = std::uint64_t(n) * n * n, cells = std::uint64_t(n - 1) * (n - 1) * (n - 1);
  std::string b;
  b.reserve(nodes * 32 + cells * 72 + 1024);
  b += "$MeshFormat\n4.1 1 8\n";
  put<std::int32_t>(b, 1);
  b += "\n$EndMeshFormat\n$PhysicalNames\n1\n3 1 \"cube\"\n$EndPhysicalNames\n$Nodes\n";
  put<std::uint64_t>(b, 1), put<std::uint64_t>(b, nodes), put<std::uint64_t>(b, 1), put<std::uint64_t>(b, nodes);
  put<std::int32_t>(b, 3), put<std::int32_t>(b, 1), put<std::int32_t>(b, 0), put<std::uint64_t>(b, nodes);
  for (std::uint64_t t = 1; t <= nodes; ++t) put<std::uint64_t>(b, t);
  const double h = 1.0 / (n - 1);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) put(b, i * h), put(b, j * h), put(b, k * h);
  b += "\n$EndNodes\n$Elements\n";
  put<std::uint64_t>(b, 1), put<std::uint64_t>(b, cells), put<std::uint64_t>(b, 1), put<std::uint64_t>(b, cells);
  put<std::int32_t>(b, 3), put<std::int32_t>(b, 1), put<std::int32_t>(b, 5), put<std::uint64_t>(b, cells);
  auto tag = [n](int i, int j, int k) { return std::uint64_t(1 + i + n * (j + n * k)); };
  std::uint64_t e = 0;
  for (int k = 0; k + 1 < n; ++k)
    for (int j = 0; j + 1 < n; ++j)
      for (int i = 0; i + 1 < n; ++i) {
        put<std::uint64_t>(b, ++e);
        for (auto t : {tag(i, j, k), tag(i + 1, j, k), tag(i + 1, j + 1, k), tag(i, j + 1, k), tag(i, j, k + 1),
                       tag(i + 1, j, k + 1), tag(i + 1, j + 1, k + 1), tag(i, j + 1, k + 1)})
          put<std::uint64_t>(b, t);
      }
  b += "\n$EndElements\n";
  return b;
}

// The n^3-node cube as a file, made and checked once per size.
const fs::path& cubeFile(int n) {
  static std::map<int, fs::path> made;
  auto it = made.find(n);
  if (it != made.end()) return it->second;
  const fs::path path = fs::temp_directory_path() / ("ffdkit-bench-gmsh-" + std::to_string(::getpid()) + "-" + std::to_string(n) + ".msh");
  const std::string bytes = cubeMsh(n);
  std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
  const meshio::GmshMesh mesh = meshio::readGmsh(path);
  const meshio::ElementQuality q = meshio::checkElementCells(mesh.points, mesh.cells);
  if (!q.ok() || std::abs(q.totalVolume - 1.0) > 1e-9) throw std::runtime_error("the cube's cells are not valid");
  const Eigen::MatrixX3d moved = mesh.points * 1.5;
  const fs::path out = path.string() + ".out.msh";
  meshio::writeGmsh(mesh, moved, out, false);
  const meshio::GmshMesh again = meshio::readGmsh(out);
  const std::string written = meshio::gmshBytes(mesh.file, moved);
  if (again.points != moved || written.substr(written.find("$Elements")) != bytes.substr(bytes.find("$Elements")))
    throw std::runtime_error("the written file does not read back");
  fs::remove(out);
  return made.emplace(n, path).first->second;
}

struct Cleanup {
  ~Cleanup() {
    std::error_code ignored;
    for (const auto& entry : fs::directory_iterator(fs::temp_directory_path(), ignored))
      if (entry.path().filename().string().rfind("ffdkit-bench-gmsh-" + std::to_string(::getpid()) + "-", 0) == 0)
        fs::remove(entry.path(), ignored);
  }
} cleanup;

int sideOf(benchmark::State& state) { return int(std::lround(std::cbrt(double(state.range(0))))); }

void BM_GmshRead(benchmark::State& state) {
  const fs::path& path = cubeFile(sideOf(state));
  for (auto _ : state) benchmark::DoNotOptimize(meshio::readGmsh(path));
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.SetBytesProcessed(state.iterations() * std::int64_t(fs::file_size(path)));
}

void BM_GmshWrite(benchmark::State& state) {
  const fs::path& path = cubeFile(sideOf(state));
  const meshio::GmshMesh mesh = meshio::readGmsh(path);
  const Eigen::MatrixX3d moved = mesh.points * 1.25;
  const fs::path out = path.string() + ".written.msh";
  for (auto _ : state) meshio::writeGmsh(mesh, moved, out, false);
  fs::remove(out);
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.SetBytesProcessed(state.iterations() * std::int64_t(fs::file_size(path)));
}

void BM_GmshCheck(benchmark::State& state) {
  const meshio::GmshMesh mesh = meshio::readGmsh(cubeFile(sideOf(state)));
  for (auto _ : state) benchmark::DoNotOptimize(meshio::checkElementCells(mesh.points, mesh.cells));
  state.SetItemsProcessed(state.iterations() * mesh.cells.cellCount());
}

}  // namespace

BENCHMARK(BM_GmshRead)->ArgName("nodes")->Arg(125000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_GmshWrite)->ArgName("nodes")->Arg(125000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_GmshCheck)->ArgName("nodes")->Arg(125000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
