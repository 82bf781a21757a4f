// A volume mesh in the app, under a real window and real events (Xvfb): the sample volume-duct
// (a Gmsh mesh of tetrahedra) opened with File > Open Scene, its boundary surface drawn, the
// pinch arrow dragged with the mouse, File > Export Deformed Mesh writing the whole mesh as a
// .msh; the file read back holds the app's deformed points and is what ffdkit-cli deform --scene
// writes for the same pinch. A pinch that folds the duct is refused with a message, and the file
// exported before stays as it was.
#include <QAction>
#include <QMessageBox>
#include <QProcess>
#include <QTemporaryDir>

#include <cstdio>
#include <filesystem>

#include "../cli/ffdkit_cli_path.h"
#include "ffdkit/meshio/volume_mesh.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "gui_test_support.h"
#include "lifecycle_dialog_answers.h"

using namespace ffdkit;
using namespace ffdkit::app::testing;
using app::MainWindow;

namespace {

namespace fs = std::filesystem;

const fs::path kDuct = FFDKIT_SOURCE_DIR "/scenes/examples/volume-duct";

// ffdkit-cli with `arguments`; its exit code (-1 when it did not run).
int runCli(const QStringList& arguments, QString* errors) {
  QProcess cli;
  cli.start(QString::fromStdString(ffdkit::test::ffdkitCli()), arguments);
  if (!cli.waitForFinished(120000)) return -1;
  *errors = QString::fromLocal8Bit(cli.readAllStandardError());
  return cli.exitStatus() == QProcess::NormalExit ? cli.exitCode() : -1;
}

}  // namespace

class VolumeMeshGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    window_ = startWindow();
    QVERIFY(window_ != nullptr);
  }
  void cleanup() { window_.reset(); }

  void aDraggedPinchIsExportedAsTheWholeMeshTheCliWrites() {
    MainWindow& w = *window_;
    {
      ModalAnswers answers({chooseFile(kDuct / "scene.json")});
      clickMenuItem(w, action(w, "actionOpenScene"));
      QTRY_COMPARE(answers.answered(), 1);
    }
    QTRY_VERIFY(w.scene().findObject("duct") != nullptr);
    const auto file = meshio::readVolumeMesh(kDuct / "duct.msh");
    const scenes::SceneObject& duct = *w.scene().findObject("duct");
    QCOMPARE(duct.mesh.points.rows(), file->points().rows());  // every point, interior ones too
    QVERIFY(duct.mesh.triangles.rows() > 0);                  // the boundary surface is what is drawn

    const widgets::WidgetId pinch = w.scene().widgets.find("pinch");
    dragArrow(w, pinch, 0.15);
    const double variation = w.scene().widgets.variation(pinch);
    QVERIFY2(variation > 0.05 && variation < 0.3, qPrintable(QString::number(variation)));
    const Eigen::MatrixX3d shown = w.deformer().points("duct");
    QVERIFY((shown - duct.mesh.points).cwiseAbs().maxCoeff() > 0.02);

    QTemporaryDir dir;
    const fs::path exported = fs::path(dir.path().toStdString()) / "pinched.msh";
    {
      ModalAnswers answers({chooseSavePath(exported)});
      clickMenuItem(w, action(w, "actionExportMesh"));
      QTRY_COMPARE(answers.answered(), 1);
    }
    QTRY_VERIFY(fs::exists(exported));
    const auto written = meshio::readVolumeMesh(exported);
    QVERIFY(written->points() == shown);  // the whole mesh, as the app deformed it
    QVERIFY(written->check(written->points()).ok());

    // The CLI with the same pinch writes the same file.
    const fs::path fromCli = fs::path(dir.path().toStdString()) / "cli.msh";
    char value[40];
    std::snprintf(value, sizeof value, "pinch=%.17g", variation);
    QString errors;
    QCOMPARE(runCli({"deform", "-q", "--scene", QString::fromStdString(kDuct.string()), "--set", value, "-o",
                     QString::fromStdString(fromCli.string())},
                    &errors),
             0);
    const Eigen::MatrixX3d cli = meshio::readVolumeMesh(fromCli)->points();
    QVERIFY2((cli - shown).cwiseAbs().maxCoeff() < 1e-12, qPrintable(QString::number((cli - shown).cwiseAbs().maxCoeff())));
    QVERIFY2(slurp(fromCli) == slurp(exported), "the app's export and the CLI's file differ");

    // Pushed through the bottom: refused with the bad cells named, the exported file unchanged.
    const std::string before = slurp(exported);
    dragArrow(w, pinch, 1.2);
    QVERIFY(w.scene().widgets.variation(pinch) > 0.8);
    QString shownMessage;
    {
      ModalAnswers answers({chooseSavePath(exported, true), readMessage(&shownMessage, QMessageBox::Critical)});
      clickMenuItem(w, action(w, "actionExportMesh"));
      QTRY_COMPARE(answers.answered(), 2);
    }
    QVERIFY2(shownMessage.contains("inverted or of zero volume") && shownMessage.contains("nothing written"),
             qPrintable(shownMessage));
    QVERIFY(slurp(exported) == before);
  }

 private:
  std::unique_ptr<MainWindow> window_;
};

int main(int argc, char** argv) { return runGuiTest<VolumeMeshGuiTest>(argc, argv); }

#include "volume_mesh_gui_test.moc"
