// A scene's CAD objects read and written through the cad module (docs/cad.md); without the module
// (FFDKIT_WITH_CAD=OFF) the reader is not registered and the writer says why.
#include "ffdkit/cad_scene/scene_cad_objects.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <variant>

#include "ffdkit/scenes/cad_objects.h"

#if FFDKIT_HAS_CAD
#include "ffdkit/cad/cad_deform.h"
#include "ffdkit/cad/cad_error.h"
#include "ffdkit/cad/cad_io.h"
#include "ffdkit/cad/tessellation.h"
#endif

namespace ffdkit::cad_scene {

namespace fs = std::filesystem;

CadUnavailableError::CadUnavailableError(const std::string& what)
    : std::runtime_error("this program was built without OpenCASCADE (FFDKIT_WITH_CAD=OFF), which " + what + " need") {}

bool isCadObject(const scenes::SceneObject& object) {
  const auto* file = std::get_if<scenes::MeshFileSource>(&object.source);
  return file != nullptr && scenes::isCadFile(file->path);
}

std::vector<const scenes::SceneObject*> cadObjects(const scenes::Scene& scene) {
  std::vector<const scenes::SceneObject*> found;
  for (const scenes::SceneObject& object : scene.objects())
    if (isCadObject(object)) found.push_back(&object);
  return found;
}

fs::path cadObjectFile(const scenes::SceneObject& object, const fs::path& baseDirectory) {
  const fs::path named(std::get<scenes::MeshFileSource>(object.source).path);
  return named.is_absolute() ? named : baseDirectory / named;
}

std::optional<widgets::WidgetId> cadObjectLattice(const scenes::Scene& scene, const scenes::SceneObject& object) {
  std::vector<widgets::WidgetId> lattices;
  for (const scenes::Attachment& attachment : scene.attachments())
    if (std::find(attachment.objects.begin(), attachment.objects.end(), object.id) != attachment.objects.end())
      lattices.push_back(attachment.lattice);
  if (lattices.empty()) return std::nullopt;
  if (lattices.size() > 1)
    throw std::runtime_error("'" + object.name + "' is deformed by " + std::to_string(lattices.size()) +
                             " lattices; a STEP or IGES output composes one lattice (detach the others)");
  if (scene.widgets.pipelineOrder(lattices.front()).size() > 1)
    throw std::runtime_error("'" + object.name + "' is deformed by lattice '" + scene.widgets.name(lattices.front()) +
                             "' and its child lattices; a STEP or IGES output composes one lattice without children");
  return lattices.front();
}

#if FFDKIT_HAS_CAD

bool builtWithCad() { return true; }

scenes::MeshData readCadObject(const fs::path& path, meshio::ReadBudget& budget,
                               const CadObjectTessellation& tessellation) {
  const cad::CadModel model = cad::readCad(path);
  cad::TessellationOptions options;
  const double size = std::max(model.bounds().diagonal().norm(), 1e-9);
  options.linearDeflection = tessellation.tolerance * size;
  options.maxEdgeLength = tessellation.maxEdgeLength * size;
  const cad::CadTriangles triangles = cad::tessellate(model, options);
  const std::string what = path.string() + ": the tessellation of its " + std::to_string(model.counts().faces) + " faces";
  budget.chargePoints(static_cast<std::uint64_t>(triangles.points.rows()), what);
  budget.chargeBytes(static_cast<std::uint64_t>(triangles.triangles.rows()), 3 * sizeof(int), what);
  scenes::MeshData mesh;
  mesh.points = triangles.points;
  mesh.triangles = triangles.triangles;
  return mesh;
}

void registerCadObjectReader(std::function<CadObjectTessellation()> tessellation) {
  scenes::setCadMeshReader([tessellation = std::move(tessellation)](const fs::path& path, meshio::ReadBudget& budget) {
    return readCadObject(path, budget, tessellation ? tessellation() : CadObjectTessellation{});
  });
}

CadObjectExport writeDeformedCadObject(const scenes::Scene& scene, const scenes::SceneObject& object,
                                       const fs::path& baseDirectory, const fs::path& output) {
  if (!cad::cadFormatOf(output))
    throw std::runtime_error(output.string() + ": a deformed CAD model is written as STEP or IGES (.step .stp .iges .igs)");
  const std::optional<widgets::WidgetId> lattice = cadObjectLattice(scene, object);
  const cad::CadModel model = cad::readCad(cadObjectFile(object, baseDirectory));
  CadObjectExport written;
  if (!lattice) {
    cad::writeCad(model, output);
    return written;
  }
  cad::CadDeformResult result;
  try {
    result = cad::deformCad(model, scene.widgets.ffdLattice(*lattice));
  } catch (const cad::CadError& e) {
    throw cad::CadError(std::string(e.what()) + ". Nothing was exported.");
  }
  cad::writeCad(result.model, output);
  const cad::CadDeformReport& report = result.report;
  written.lattice = scene.widgets.name(*lattice);
  written.faces = report.faces;
  written.maxDegree = report.maxDegree;
  written.approximatedFaces = report.approximatedFaces;
  written.approximatedEdges = report.approximatedEdges;
  written.tolerance = report.tolerance;
  written.approximationError = report.approximationError;
  return written;
}

#else

bool builtWithCad() { return false; }

scenes::MeshData readCadObject(const fs::path&, meshio::ReadBudget&, const CadObjectTessellation&) {
  throw CadUnavailableError("STEP and IGES objects");
}

void registerCadObjectReader(std::function<CadObjectTessellation()>) {}  // scenes' own error names the file

CadObjectExport writeDeformedCadObject(const scenes::Scene&, const scenes::SceneObject&, const fs::path&,
                                       const fs::path&) {
  throw CadUnavailableError("STEP and IGES outputs");
}

#endif

}  // namespace ffdkit::cad_scene
