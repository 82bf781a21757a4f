// STEP parts in the app under a real window and real events (Xvfb): File > Import Mesh... opens a
// STEP file through the file dialog and shows its tessellation; a scene naming the STEP file opens
// through File > Open Scene...; an arrow dragged with the mouse deforms the tessellation live, and
// File > Export Deformed CAD Model... writes the exact deformation: re-read with cad_io, it is
// cad::deformCad of the same part by the same lattice, a valid solid whose volume is the volume
// the deformed triangles shown enclose. A scene without a CAD object exports nothing and says why.
#include <QAction>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QInputDialog>
#include <QMessageBox>
#include <QSettings>
#include <QTemporaryDir>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "ffdkit/cad/cad_check.h"
#include "ffdkit/cad/cad_deform.h"
#include "ffdkit/cad/cad_io.h"
#include "ffdkit/cad/sample_parts.h"
#include "ffdkit/cad/tessellation.h"
#include "ffdkit/scenes/scene_file.h"
#include "gui_test_support.h"
#include "lifecycle_dialog_answers.h"

using namespace ffdkit;
using namespace ffdkit::app::testing;
using app::MainWindow;

namespace {

namespace fs = std::filesystem;

// The filleted box (60 x 40 x 30, every edge rounded with radius 5): a box shrunk by r on every
// side, swept by a ball of radius r (Steiner's formula).
double filletedBoxVolume() {
  const double a = 50.0, b = 30.0, c = 20.0, r = 5.0;
  return a * b * c + 2.0 * r * (a * b + b * c + a * c) + std::numbers::pi * r * r * (a + b + c) +
         4.0 / 3.0 * std::numbers::pi * r * r * r;
}

// The tessellation the app shows for a part (its default import tolerance, 1e-3 of the size, and
// edges up to 2% of the size).
cad::CadTriangles defaultTessellation(const cad::CadModel& part, double tolerance = 1e-3) {
  cad::TessellationOptions options;
  options.linearDeflection = tolerance * part.bounds().diagonal().norm();
  options.maxEdgeLength = 0.02 * part.bounds().diagonal().norm();
  return cad::tessellate(part, options);
}

}  // namespace

class CadGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    folder_ = dir_.path().toStdString();
    cad::writeStep(cad::makeSamplePart(cad::SamplePart::FilletedBox), folder_ / "part.step");
  }
  void init() {
    window_ = startWindow();
    QVERIFY(window_ != nullptr);
  }
  void cleanup() {
    window_.reset();
    QSettings().remove("cadTessellationTolerance");  // every test imports with the default
  }

  void importingAStepFileShowsItsTessellation() {
    MainWindow& w = *window_;
    {
      ModalAnswers answers({chooseFile(folder_ / "part.step")});
      clickMenuItem(w, action(w, "actionImportMesh"));
      QTRY_COMPARE(answers.answered(), 1);
    }
    QTRY_COMPARE(w.scene().objects().size(), std::size_t(1));
    const scenes::SceneObject& object = w.scene().objects().front();
    QCOMPARE(QString::fromStdString(object.name), QString("part"));
    const cad::CadTriangles expected = defaultTessellation(cad::readStep(folder_ / "part.step"));
    QCOMPARE(object.mesh.points.rows(), expected.points.rows());
    QVERIFY(object.mesh.points == expected.points);
    QVERIFY(object.mesh.triangles == expected.triangles);
    // The triangles enclose the part: the filleted box's volume within the tessellation's error.
    const double volume = cad::enclosedVolume(object.mesh.points, object.mesh.triangles);
    QVERIFY2(std::abs(volume - filletedBoxVolume()) < 2e-3 * filletedBoxVolume(),
             qPrintable(QString("%1 vs %2").arg(volume).arg(filletedBoxVolume())));
  }

  void theTessellationToleranceTypedInItsDialogHoldsForTheNextImport() {
    MainWindow& w = *window_;
    {
      ModalAnswers answers({[](QWidget* modal) {
        auto* dialog = qobject_cast<QInputDialog*>(modal);
        QVERIFY2(dialog != nullptr && dialog->objectName() == "cadTessellationDialog", qPrintable(modal->objectName()));
        auto* spin = dialog->findChild<QDoubleSpinBox*>();
        QVERIFY(spin != nullptr);
        spin->selectAll();
        QTest::keyClicks(spin, "0.02");
        auto* buttons = dialog->findChild<QDialogButtonBox*>();
        QVERIFY(buttons != nullptr);
        QTest::mouseClick(buttons->button(QDialogButtonBox::Ok), Qt::LeftButton);
      }});
      clickMenuItem(w, action(w, "actionCadTessellation"));
      QTRY_COMPARE(answers.answered(), 1);
    }
    {
      ModalAnswers answers({chooseFile(folder_ / "part.step")});
      clickMenuItem(w, action(w, "actionImportMesh"));
      QTRY_COMPARE(answers.answered(), 1);
    }
    QTRY_COMPARE(w.scene().objects().size(), std::size_t(1));
    const cad::CadModel part = cad::readStep(folder_ / "part.step");
    const cad::CadTriangles coarse = defaultTessellation(part, 0.02);
    QVERIFY(w.scene().objects().front().mesh.points == coarse.points);
    const cad::CadTriangles fine = defaultTessellation(part);
    QVERIFY(coarse.points.rows() != fine.points.rows() || coarse.points != fine.points);
  }

  void aDraggedArrowExportsTheExactDeformation() {
    MainWindow& w = *window_;
    // A scene naming the STEP file, with a 3 x 3 x 3 lattice and an arrow on its top centre point.
    const cad::CadModel part = cad::readStep(folder_ / "part.step");
    const Eigen::AlignedBox3d box = part.bounds();
    const double size = box.diagonal().norm();
    {
      scenes::Scene scene;
      scenes::SceneObject object;
      object.name = "part";
      object.source = scenes::MeshFileSource{"part.step"};
      const cad::CadTriangles triangles = defaultTessellation(part);
      object.mesh.points = triangles.points;
      object.mesh.triangles = triangles.triangles;
      scene.addObject(std::move(object));
      scenes::AttachOptions attach;
      attach.latticeName = "lattice";
      const auto lattice = scenes::attachNewLattice(scene, {"part"}, attach);
      const auto top = scene.widgets.addCell(lattice, widgets::CellSpec::point(1, 1, 2), "top");
      widgets::AffineOptions up;
      up.name = "pull";
      up.placement = Eigen::AngleAxisd(-std::numbers::pi / 2, Eigen::Vector3d::UnitY());  // local x -> world +z
      scene.widgets.addAffine(top, widgets::AffineKind::Translate, up);
      scenes::Camera camera = scene.camera();
      camera.focalPoint = box.center();
      camera.position = box.center() + size * Eigen::Vector3d(1.2, -1.6, 1.1);
      scene.setCamera(camera);
      scenes::writeScene(folder_ / "scene.json", scene);
    }
    {
      ModalAnswers answers({chooseFile(folder_ / "scene.json")});
      clickMenuItem(w, action(w, "actionOpenScene"));
      QTRY_COMPARE(answers.answered(), 1);
    }
    QTRY_COMPARE(w.documentPath(), folder_ / "scene.json");
    QCOMPARE(w.scene().objects().size(), std::size_t(1));
    QVERIFY(w.scene().objects().front().mesh.points == defaultTessellation(part).points);

    const widgets::WidgetId lattice = w.scene().widgets.find("lattice");
    const Eigen::MatrixX3d restLattice = w.scene().widgets.worldControlPoints(lattice);
    dragArrow(w, w.scene().widgets.find("pull"), 0.15 * size);
    const double moved = (w.scene().widgets.worldControlPoints(lattice) - restLattice).rowwise().norm().maxCoeff();
    QVERIFY2(moved > 0.05 * size, qPrintable(QString("the drag moved the lattice by %1").arg(moved)));
    const Eigen::MatrixX3d shown = w.deformer().points("part");
    const double shownVolume = cad::enclosedVolume(shown, w.scene().objects().front().mesh.triangles);
    QVERIFY2(shownVolume > 1.02 * filletedBoxVolume(), qPrintable(QString::number(shownVolume)));

    const fs::path output = folder_ / "deformed.step";
    {
      ModalAnswers answers({chooseSavePath(output)});
      clickMenuItem(w, action(w, "actionExportCad"));
      QTRY_COMPARE(answers.answered(), 1);
    }
    QTRY_VERIFY(fs::exists(output));
    QVERIFY2(w.statusMessage().contains("deformed exactly"), qPrintable(w.statusMessage()));

    const cad::CadModel written = cad::readStep(output);
    const cad::CadModel expected = cad::deformCad(part, w.scene().widgets.ffdLattice(lattice)).model;
    QCOMPARE(written.counts().faces, expected.counts().faces);
    QCOMPARE(written.counts().solids, 1);
    const cad::CadCheck writtenCheck = cad::checkModel(written);
    const cad::CadCheck expectedCheck = cad::checkModel(expected);
    QVERIFY2(writtenCheck.valid, writtenCheck.firstProblem.c_str());
    QVERIFY2(std::abs(writtenCheck.volume - expectedCheck.volume) < 1e-9 * expectedCheck.volume,
             qPrintable(QString("%1 vs %2").arg(writtenCheck.volume, 0, 'g', 17).arg(expectedCheck.volume, 0, 'g', 17)));
    // Bounding boxes are widened by the shapes' tolerances, which a STEP file carries rounded.
    const double slack = 2.0 * std::max(writtenCheck.maxTolerance, expectedCheck.maxTolerance) + 1e-9 * size;
    const double boundsGap = std::max((written.bounds().min() - expected.bounds().min()).cwiseAbs().maxCoeff(),
                                      (written.bounds().max() - expected.bounds().max()).cwiseAbs().maxCoeff());
    QVERIFY2(boundsGap < slack, qPrintable(QString("%1 vs %2").arg(boundsGap).arg(slack)));
    // The triangles shown are the FFD of the part's tessellation: they enclose the written solid's
    // volume within the tessellation's error.
    QVERIFY2(std::abs(writtenCheck.volume - shownVolume) < 2e-3 * shownVolume,
             qPrintable(QString("%1 vs %2").arg(writtenCheck.volume).arg(shownVolume)));
  }

  void aSceneWithoutACadObjectExportsNothingAndSaysWhy() {
    MainWindow& w = *window_;
    w.openScene(kExamples / "default");
    const fs::path output = folder_ / "nothing.step";
    QString shown;
    {
      ModalAnswers answers({chooseSavePath(output), readMessage(&shown, QMessageBox::Critical)});
      clickMenuItem(w, action(w, "actionExportCad"));
      QTRY_COMPARE(answers.answered(), 2);
    }
    QVERIFY2(shown.contains("no object read from a STEP or IGES file"), qPrintable(shown));
    QVERIFY(!fs::exists(output));
  }

 private:
  QTemporaryDir dir_;
  fs::path folder_;
  std::unique_ptr<MainWindow> window_;
};

int main(int argc, char** argv) { return runGuiTest<CadGuiTest>(argc, argv); }

#include "cad_gui_test.moc"
