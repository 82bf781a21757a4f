// An OpenFOAM case through what `ffdkit-cli deform` does with it, step by step and whole:
//   BM_OpenFoamRead/cells:64      read the binary polyMesh of a cube of 64^3 hexahedra
//   BM_OpenFoamDeform/cells:64    deform its points with tests/data/openfoam/bulge.json (scenes::SceneDeformer)
//   BM_OpenFoamDeformInPlace/cells:64  the same points in place (ffd::deformInPlace), as the CLI does
//   BM_OpenFoamCheck/cells:64     the cell check (meshio/cell_quality.h)
//   BM_OpenFoamCheckDeformed/cells:64  the cell check of the deformed points, as the CLI runs it
//   BM_OpenFoamWrite/cells:64     write the case (points rewritten, the rest copied; durable)
//   BM_OpenFoamCase/cells:64      all four, as the CLI runs them, deforming in place (also at 215^3
//                                 cells, 10M points)
//   BM_OpenFoamCaseNotFlushed/cells:215  the same with the written files left in the page cache
// The case is what blockMesh writes for a unit cube of N^3 cells in binary (foamFormatConvert):
// points x fastest, internal faces in upper-triangular order, one boundary patch; made here from
// the cell-check tests' cube (tests/meshio/polymesh_cube.h), so that the benchmark needs no OpenFOAM. Each size is first checked: the cube's cells are valid,
// their volumes add up to 1, and the written case reads back with the deformed points.
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <stdexcept>
#include <string>
#include <vector>

#include "ffdkit/ffd/in_place_deform.h"
#include "ffdkit/meshio/cell_quality.h"
#include "ffdkit/meshio/openfoam.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/widget_file.h"
#include "polymesh_cube.h"

namespace {

using namespace ffdkit;
namespace fs = std::filesystem;

// Read options for the points alone (no faces, owner, neighbour or boundary).
meshio::OpenFoamReadOptions pointsOnly() {
  meshio::OpenFoamReadOptions options;
  options.readCells = false;
  return options;
}

std::string header(const char* className, const char* object) {
  return std::string("FoamFile\n{\n    version     2.0;\n    format      binary;\n    class       ") + className +
         ";\n    arch        \"LSB;label=32;scalar=64\";\n    location    \"constant/polyMesh\";\n    object      " +
         object + ";\n}\n\n";
}

template <class T>
void appendList(std::string& out, const std::vector<T>& values) {
  out += std::to_string(values.size()) + "\n(";
  out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  out += ")\n";
}

void appendList(std::string& out, const meshio::LabelList& labels) {
  out += std::to_string(labels.size()) + "\n(";
  out.append(labels.bytes(), labels.size() * sizeof(std::int32_t));
  out += ")\n";
}

void writeFile(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

// The cases made by this run, removed at its end.
struct MadeCases {
  std::vector<fs::path> roots;
  ~MadeCases() {
    std::error_code ignored;
    for (const auto& root : roots) fs::remove_all(root, ignored);
  }
};

// A case folder holding the binary polyMesh of a unit cube of n^3 hexahedra.
fs::path makeCube(int n) {
  static MadeCases made;
  const fs::path root = fs::temp_directory_path() / ("ffdkit-bench-openfoam-" + std::to_string(::getpid()) + "-" + std::to_string(n));
  if (fs::exists(root / "constant" / "polyMesh" / "boundary")) return root;
  made.roots.push_back(root);
  const fs::path polyMesh = root / "constant" / "polyMesh";
  fs::create_directories(polyMesh);
  fs::create_directories(root / "system");
  writeFile(root / "system" / "controlDict", "FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n");
  const meshio::test::PolyMeshCube cube = meshio::test::polyMeshCube(n);
  const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> coordinates = cube.points;  // x y z of each point in turn
  const meshio::PolyMeshCells& cells = cube.cells;
  std::string bytes = header("vectorField", "points");
  bytes += std::to_string(coordinates.rows()) + "\n(";
  bytes.append(reinterpret_cast<const char*>(coordinates.data()), std::size_t(coordinates.size()) * sizeof(double));
  bytes += ")\n";
  writeFile(polyMesh / "points", bytes);
  bytes = header("faceCompactList", "faces");
  appendList(bytes, cells.faceStarts);
  appendList(bytes, cells.faceVertices);
  writeFile(polyMesh / "faces", bytes);
  bytes = header("labelList", "owner");
  appendList(bytes, cells.owner);
  writeFile(polyMesh / "owner", bytes);
  bytes = header("labelList", "neighbour");
  appendList(bytes, cells.neighbour);
  writeFile(polyMesh / "neighbour", bytes);
  writeFile(polyMesh / "boundary",
            "FoamFile { version 2.0; format ascii; class polyBoundaryMesh; object boundary; }\n1\n(\n    walls\n    {\n"
            "        type wall;\n        nFaces " + std::to_string(6 * n * n) + ";\n        startFace " +
            std::to_string(cells.neighbour.size()) + ";\n    }\n)\n");
  return root;
}

widgets::WidgetModel tool() {
  return scenes::readWidgetFile(fs::path(FFDKIT_SOURCE_DIR) / "tests" / "data" / "openfoam" / "bulge.json");
}

Eigen::MatrixX3d deform(const widgets::WidgetModel& model, Eigen::MatrixX3d points) {
  scenes::Scene scene;
  scene.widgets = model;
  scenes::SceneObject object;
  object.name = "mesh";
  object.mesh.points = std::move(points);
  const scenes::ObjectId id = scene.addObject(std::move(object));
  std::vector<scenes::Attachment> attachments;
  for (auto root : scene.widgets.roots()) attachments.push_back({root, {id}});
  scene.setAttachments(std::move(attachments));
  scenes::SceneDeformer deformer;
  deformer.evaluateTakingPoints(scene);
  return deformer.takePoints(id);
}

// The tool's one lattice, as the scene deformer builds it.
ffd::Lattice toolLattice(const widgets::WidgetModel& model) { return model.ffdLattice(model.roots().front()); }

void checkCube(int n) {
  const meshio::OpenFoamMesh mesh = meshio::readOpenFoamMesh(makeCube(n));
  const meshio::CellQuality before = meshio::checkPolyMeshCells(mesh.points, mesh.cells);
  if (!before.ok() || std::abs(before.totalVolume - 1.0) > 1e-9 || before.cellCount != std::int64_t(n) * n * n)
    throw std::runtime_error("the generated cube is not valid: " + meshio::cellQualityText(before));
  const Eigen::MatrixX3d deformed = deform(tool(), mesh.points);
  if (!meshio::checkPolyMeshCells(deformed, mesh.cells).ok()) throw std::runtime_error("bulge.json inverted cells");
  Eigen::MatrixX3d inPlace = mesh.points;
  ffd::deformInPlace(toolLattice(tool()), inPlace);
  if (inPlace != deformed) throw std::runtime_error("deformInPlace gives other points than the scene deformer");
  const fs::path out = makeCube(n).string() + "-out";
  meshio::writeOpenFoamMesh(mesh, deformed, out, {.durable = false});
  if (meshio::readOpenFoamMesh(out, pointsOnly()).points != deformed)
    throw std::runtime_error("the written case reads back other points");
  fs::remove_all(out);
}

int cellsOf(const benchmark::State& state) {
  static int checked = 0;
  const int n = int(state.range(0));
  if (checked != n) {
    checkCube(n);
    checked = n;
  }
  return n;
}

void setCounters(benchmark::State& state, int n) {
  const double points = std::pow(double(n + 1), 3);
  state.counters["points"] = points;
  state.counters["points_per_second"] = benchmark::Counter(points * double(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_OpenFoamRead(benchmark::State& state) {
  const int n = cellsOf(state);
  const fs::path root = makeCube(n);
  for (auto _ : state) benchmark::DoNotOptimize(meshio::readOpenFoamMesh(root).points.data());
  setCounters(state, n);
}

void BM_OpenFoamDeform(benchmark::State& state) {
  const int n = cellsOf(state);
  const meshio::OpenFoamMesh mesh = meshio::readOpenFoamMesh(makeCube(n), pointsOnly());
  const widgets::WidgetModel model = tool();
  for (auto _ : state) benchmark::DoNotOptimize(deform(model, mesh.points).data());
  setCounters(state, n);
}

void BM_OpenFoamDeformInPlace(benchmark::State& state) {
  const int n = cellsOf(state);
  const meshio::OpenFoamMesh mesh = meshio::readOpenFoamMesh(makeCube(n), pointsOnly());
  const ffd::Lattice lattice = toolLattice(tool());
  Eigen::MatrixX3d points = mesh.points;
  for (auto _ : state) {
    state.PauseTiming();
    points = mesh.points;
    state.ResumeTiming();
    ffd::deformInPlace(lattice, points);
    benchmark::DoNotOptimize(points.data());
  }
  setCounters(state, n);
}

void BM_OpenFoamCheck(benchmark::State& state) {
  const int n = cellsOf(state);
  const meshio::OpenFoamMesh mesh = meshio::readOpenFoamMesh(makeCube(n));
  for (auto _ : state) benchmark::DoNotOptimize(meshio::checkPolyMeshCells(mesh.points, mesh.cells).minVolume);
  setCounters(state, n);
}

void BM_OpenFoamCheckDeformed(benchmark::State& state) {
  const int n = cellsOf(state);
  const meshio::OpenFoamMesh mesh = meshio::readOpenFoamMesh(makeCube(n));
  Eigen::MatrixX3d points = mesh.points;
  ffd::deformInPlace(toolLattice(tool()), points);
  for (auto _ : state) benchmark::DoNotOptimize(meshio::checkPolyMeshCells(points, mesh.cells).minVolume);
  setCounters(state, n);
}

void BM_OpenFoamWrite(benchmark::State& state) {
  const int n = cellsOf(state);
  const fs::path root = makeCube(n);
  const meshio::OpenFoamMesh mesh = meshio::readOpenFoamMesh(root, pointsOnly());
  const Eigen::MatrixX3d moved = mesh.points * 1.01;
  const fs::path out = root.string() + "-out";
  for (auto _ : state) meshio::writeOpenFoamMesh(mesh, moved, out);
  fs::remove_all(out);
  setCounters(state, n);
}

// All four steps; the written files flushed to disk (as the CLI does) or left to the page cache.
// `overlapped`: as ffdkit-cli deform does it, the case written to a hidden folder on a thread of
// its own while the cells are checked (stageOpenFoamMesh), put in place once the check passes;
// else the write after the check, on every core.
void runCase(benchmark::State& state, bool durable, bool overlapped = false) {
  const int n = cellsOf(state);
  const fs::path root = makeCube(n);
  const fs::path out = root.string() + "-out";
  const ffd::Lattice lattice = toolLattice(tool());
  for (auto _ : state) {
    meshio::OpenFoamMesh mesh = meshio::readOpenFoamMesh(root);
    ffd::deformInPlace(lattice, mesh.points);
    if (!overlapped) {
      if (!meshio::checkPolyMeshCells(mesh.points, mesh.cells).ok()) state.SkipWithError("inverted cells");
      meshio::writeOpenFoamMesh(mesh, mesh.points, out, {.durable = durable});
      continue;
    }
    auto staging = std::async(std::launch::async, [&] {
      return meshio::stageOpenFoamMesh(mesh, mesh.points, out, {.durable = durable, .everyCore = false});
    });
    const bool ok = meshio::checkPolyMeshCells(mesh.points, mesh.cells).ok();
    meshio::StagedOpenFoamMesh staged = staging.get();
    if (!ok) state.SkipWithError("inverted cells");
    else staged.commit();
  }
  fs::remove_all(out);
  setCounters(state, n);
}

void BM_OpenFoamCase(benchmark::State& state) { runCase(state, true); }
void BM_OpenFoamCaseNotFlushed(benchmark::State& state) { runCase(state, false); }
void BM_OpenFoamCaseOverlapped(benchmark::State& state) { runCase(state, true, true); }

// CPU time is the whole process's (the deformation and the cell check run on every core).
void sizes(benchmark::internal::Benchmark* b) {
  b->ArgName("cells")->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
  for (int n : {32, 64, 128}) b->Arg(n);
}

BENCHMARK(BM_OpenFoamRead)->Apply(sizes);
BENCHMARK(BM_OpenFoamDeform)->Apply(sizes);
BENCHMARK(BM_OpenFoamDeformInPlace)->Apply(sizes);
BENCHMARK(BM_OpenFoamCheck)->Apply(sizes);
BENCHMARK(BM_OpenFoamCheckDeformed)->Apply(sizes);
BENCHMARK(BM_OpenFoamWrite)->Apply(sizes);
BENCHMARK(BM_OpenFoamCase)->Apply(sizes);
BENCHMARK(BM_OpenFoamCaseOverlapped)->Apply(sizes);
// The 10M-point case (215^3 cells, 10,077,696 points), the whole run only, one pass per repetition.
BENCHMARK(BM_OpenFoamCase)
    ->ArgName("cells")->Arg(215)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime()->Iterations(1);
// The same without the flush to disk: what the disk's share of the run is.
BENCHMARK(BM_OpenFoamCaseNotFlushed)
    ->ArgName("cells")->Arg(215)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime()->Iterations(1);
// The write beside the check, as ffdkit-cli deform does it.
BENCHMARK(BM_OpenFoamCaseOverlapped)
    ->ArgName("cells")->Arg(215)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime()->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
