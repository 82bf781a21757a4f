// The app's Qt side of STEP and IGES parts: the tessellation tolerance setting and its dialog, and
// the export's status line. Reading and writing them is cad_scene's (scene_cad_objects.h), shared
// with ffdkit-cli.
#include "cad_import.h"

#include <stdexcept>
#include <string>
#include <vector>

#include <QAction>
#include <QInputDialog>
#include <QMenu>
#include <QSettings>
#include <QWidget>

#include "ffdkit/cad_scene/scene_cad_objects.h"

namespace ffdkit::app {

namespace {

QString qs(const std::string& s) { return QString::fromStdString(s); }

// The CAD object to export: the first selected object read from a CAD file, else the scene's only one.
const scenes::SceneObject& cadObjectToExport(const scenes::Scene& scene, const std::vector<std::string>& selected) {
  for (const std::string& name : selected)
    if (const scenes::SceneObject* object = scene.findObject(name); object != nullptr && cad_scene::isCadObject(*object))
      return *object;
  const std::vector<const scenes::SceneObject*> found = cad_scene::cadObjects(scene);
  if (found.empty())
    throw std::runtime_error("the scene has no object read from a STEP or IGES file (File > Import Mesh... opens one)");
  if (found.size() > 1) throw std::runtime_error("the scene has several CAD objects: select the one to export (in the outliner)");
  return *found.front();
}

}  // namespace

bool hasCadModule() { return cad_scene::builtWithCad(); }

double cadTessellationTolerance() {
  const double fallback = cad_scene::CadObjectTessellation{}.tolerance;
  const double value = QSettings().value(kCadTessellationKey, fallback).toDouble();
  return value >= cad_scene::kSmallestTessellationTolerance && value <= cad_scene::kLargestTessellationTolerance ? value
                                                                                                                 : fallback;
}

void registerCadObjectReader() {
  cad_scene::registerCadObjectReader([] {
    cad_scene::CadObjectTessellation tessellation;
    tessellation.tolerance = cadTessellationTolerance();
    return tessellation;
  });
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
    dialog.setDoubleRange(cad_scene::kSmallestTessellationTolerance, cad_scene::kLargestTessellationTolerance);
    dialog.setDoubleValue(cadTessellationTolerance());
    if (dialog.exec() == QDialog::Accepted) QSettings().setValue(kCadTessellationKey, dialog.doubleValue());
  });
}

QString exportDeformedCad(const scenes::Scene& scene, const std::vector<std::string>& selected,
                          const std::filesystem::path& baseDirectory, const std::filesystem::path& output) {
  if (!hasCadModule()) throw cad_scene::CadUnavailableError("STEP and IGES exports");
  const scenes::SceneObject& object = cadObjectToExport(scene, selected);
  const cad_scene::CadObjectExport written = cad_scene::writeDeformedCadObject(scene, object, baseDirectory, output);
  if (written.lattice.empty())
    return QObject::tr("Exported '%1' to %2 as read: no lattice deforms it").arg(qs(object.name), qs(output.string()));
  if (written.approximatedFaces == 0 && written.approximatedEdges == 0)
    return QObject::tr("Exported '%1' deformed exactly by '%2' to %3 (%4 faces, degree up to %5)")
        .arg(qs(object.name), qs(written.lattice), qs(output.string()))
        .arg(written.faces)
        .arg(written.maxDegree);
  // Exact where the FFD is one polynomial per piece; the rest fitted to deformCad's tolerance.
  return QObject::tr("Exported '%1' deformed by '%2' to %3: %4 of %5 faces and %6 edges approximated "
                     "(largest error %7, tolerance %8), the rest exact")
      .arg(qs(object.name), qs(written.lattice), qs(output.string()))
      .arg(written.approximatedFaces)
      .arg(written.faces)
      .arg(written.approximatedEdges)
      .arg(written.approximationError, 0, 'g', 3)
      .arg(written.tolerance, 0, 'g', 3);
}

}  // namespace ffdkit::app
