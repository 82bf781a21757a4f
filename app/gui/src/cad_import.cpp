#include "cad_import.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <QAction>
#include <QInputDialog>
#include <QMenu>
#include <QSettings>
#include <QWidget>

#include "ffdkit/scenes/cad_objects.h"

#if FFDKIT_HAS_CAD
#include "ffdkit/cad/cad_deform.h"
#include "ffdkit/cad/cad_error.h"
#include "ffdkit/cad/cad_io.h"
#include "ffdkit/cad/tessellation.h"
#endif

namespace ffdkit::app {

namespace {

namespace fs = std::filesystem;

constexpr double kDefaultTolerance = 1e-3;
constexpr double kSmallestTolerance = 1e-6;
constexpr double kLargestTolerance = 0.1;
// The longest triangle edge of an imported part, relative to its size: a lattice bends the
// triangles of a plane too (BRepMesh gives a plane its boundary's points only).
constexpr double kMaxEdgeLength = 0.02;

}  // namespace

double cadTessellationTolerance() {
  const double value = QSettings().value(kCadTessellationKey, kDefaultTolerance).toDouble();
  return value >= kSmallestTolerance && value <= kLargestTolerance ? value : kDefaultTolerance;
}

void addCadTessellationAction(QMenu* file, QWidget* parent) {
  QAction* a = file->addAction(QObject::tr("CAD &Tessellation Tolerance..."));
  a->setObjectName("actionCadTessellation");
  a->setEnabled(hasCadModule());
  if (!hasCadModule()) a->setToolTip(QObject::tr("This build has no CAD module (OpenCASCADE): it reads no STEP or IGES"));
  QObject::connect(a, &QAction::triggered, parent, [parent] {
    QInputDialog dialog(parent);
    dialog.setObjectName("cadTessellationDialog");
    dialog.setWindowTitle(QObject::tr("CAD Tessellation Tolerance"));
    dialog.setLabelText(QObject::tr("Largest distance between the triangles shown and a STEP or IGES part's\n"
                                    "surfaces, as a fraction of the part's size (for the next imports):"));
    dialog.setInputMode(QInputDialog::DoubleInput);
    dialog.setDoubleDecimals(6);
    dialog.setDoubleRange(kSmallestTolerance, kLargestTolerance);
    dialog.setDoubleValue(cadTessellationTolerance());
    if (dialog.exec() == QDialog::Accepted) QSettings().setValue(kCadTessellationKey, dialog.doubleValue());
  });
}

#if FFDKIT_HAS_CAD

namespace {

QString qs(const std::string& s) { return QString::fromStdString(s); }

// The CAD object to export: the first selected object read from a CAD file, else the scene's only one.
const scenes::SceneObject& cadObjectToExport(const scenes::Scene& scene, const std::vector<std::string>& selected) {
  const auto isCad = [](const scenes::SceneObject& object) {
    const auto* file = std::get_if<scenes::MeshFileSource>(&object.source);
    return file != nullptr && scenes::isCadFile(file->path);
  };
  for (const std::string& name : selected)
    if (const scenes::SceneObject* object = scene.findObject(name); object != nullptr && isCad(*object)) return *object;
  const scenes::SceneObject* found = nullptr;
  int count = 0;
  for (const scenes::SceneObject& object : scene.objects())
    if (isCad(object)) found = &object, ++count;
  if (count == 0)
    throw std::runtime_error("the scene has no object read from a STEP or IGES file (File > Import Mesh... opens one)");
  if (count > 1) throw std::runtime_error("the scene has several CAD objects: select the one to export (in the outliner)");
  return *found;
}

}  // namespace

bool hasCadModule() { return true; }

void registerCadObjectReader() {
  scenes::setCadMeshReader([](const fs::path& path, meshio::ReadBudget& budget) {
    const cad::CadModel model = cad::readCad(path);
    cad::TessellationOptions options;
    const double size = std::max(model.bounds().diagonal().norm(), 1e-9);
    options.linearDeflection = cadTessellationTolerance() * size;
    options.maxEdgeLength = kMaxEdgeLength * size;  // planes get inner points to bend
    const cad::CadTriangles triangles = cad::tessellate(model, options);
    const std::string what = path.string() + ": the tessellation of its " + std::to_string(model.counts().faces) + " faces";
    budget.chargePoints(static_cast<std::uint64_t>(triangles.points.rows()), what);
    budget.chargeBytes(static_cast<std::uint64_t>(triangles.triangles.rows()), 3 * sizeof(int), what);
    scenes::MeshData mesh;
    mesh.points = triangles.points;
    mesh.triangles = triangles.triangles;
    return mesh;
  });
}

QString exportDeformedCad(const scenes::Scene& scene, const std::vector<std::string>& selected,
                          const fs::path& baseDirectory, const fs::path& output) {
  if (!cad::cadFormatOf(output))
    throw std::runtime_error(output.string() + ": a deformed CAD model is written as STEP or IGES (.step .stp .iges .igs)");
  const scenes::SceneObject& object = cadObjectToExport(scene, selected);
  const fs::path named = std::get<scenes::MeshFileSource>(object.source).path;
  const fs::path source = named.is_absolute() ? named : baseDirectory / named;
  std::vector<widgets::WidgetId> lattices;
  for (const scenes::Attachment& attachment : scene.attachments())
    if (std::find(attachment.objects.begin(), attachment.objects.end(), object.id) != attachment.objects.end())
      lattices.push_back(attachment.lattice);
  const cad::CadModel model = cad::readCad(source);
  if (lattices.empty()) {
    cad::writeCad(model, output);
    return QObject::tr("Exported '%1' to %2 as read: no lattice deforms it").arg(qs(object.name), qs(output.string()));
  }
  if (lattices.size() > 1)
    throw std::runtime_error("'" + object.name + "' is deformed by " + std::to_string(lattices.size()) +
                             " lattices; the exact CAD export composes one lattice (detach the others)");
  if (scene.widgets.pipelineOrder(lattices.front()).size() > 1)
    throw std::runtime_error("'" + object.name + "' is deformed by lattice '" + scene.widgets.name(lattices.front()) +
                             "' and its child lattices; the exact CAD export composes one lattice without children");
  cad::CadDeformResult result;
  try {
    result = cad::deformCad(model, scene.widgets.ffdLattice(lattices.front()));
  } catch (const cad::CadError& e) {
    throw cad::CadError(std::string(e.what()) + ". Nothing was exported.");
  }
  cad::writeCad(result.model, output);
  const cad::CadDeformReport& report = result.report;
  if (report.approximatedFaces == 0 && report.approximatedEdges == 0)
    return QObject::tr("Exported '%1' deformed exactly by '%2' to %3 (%4 faces, degree up to %5)")
        .arg(qs(object.name), qs(scene.widgets.name(lattices.front())), qs(output.string()))
        .arg(report.faces)
        .arg(report.maxDegree);
  // Exact where the FFD is one polynomial per piece; the rest fitted to deformCad's tolerance.
  return QObject::tr("Exported '%1' deformed by '%2' to %3: %4 of %5 faces and %6 edges approximated "
                     "(largest error %7, tolerance %8), the rest exact")
      .arg(qs(object.name), qs(scene.widgets.name(lattices.front())), qs(output.string()))
      .arg(report.approximatedFaces)
      .arg(report.faces)
      .arg(report.approximatedEdges)
      .arg(report.approximationError, 0, 'g', 3)
      .arg(report.tolerance, 0, 'g', 3);
}

#else

bool hasCadModule() { return false; }

void registerCadObjectReader() {}

QString exportDeformedCad(const scenes::Scene&, const std::vector<std::string>&, const fs::path&, const fs::path&) {
  throw std::runtime_error("this ffdkit was built without the CAD module (OpenCASCADE, FFDKIT_WITH_CAD=OFF): it "
                           "cannot export STEP or IGES");
}

#endif

}  // namespace ffdkit::app
