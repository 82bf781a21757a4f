// A full disk while the app saves, autosaves and exports (a deformed mesh, glTF), and while
// ffdkit-cli deforms and exports: the file that was there stays byte for byte, no temporary is
// left, the user reads what failed, and the app goes on (a following edit and save succeed).
// The disk fills by RLIMIT_FSIZE: with SIGXFSZ ignored, a write past the limit fails with EFBIG
// ("File too large") as a write to a full disk fails with ENOSPC; the writers handle both alike.
#include <QAction>
#include <QDialogButtonBox>
#include <QLineEdit>
#include <QProcess>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <memory>

#include <sys/resource.h>

#include "../cli/ffdkit_cli_path.h"
#include "ffdkit/gui/recovery_file.h"
#include "ffdkit/meshio/mesh_io.h"
#include "ffdkit/scenes/scene_file.h"
#include "gui_test_support.h"
#include "lifecycle_dialog_answers.h"

using namespace ffdkit;
using namespace ffdkit::app::testing;
using app::MainWindow;

namespace {

namespace fs = std::filesystem;

// A file grown past this fails to write (every file the fixture writes is larger).
constexpr rlim_t kFullAfterBytes = 1024;
const QString kDiskFull = QString::fromLocal8Bit(std::strerror(EFBIG));

// While it lives, no file of this process grows past kFullAfterBytes.
class FullDisk {
 public:
  FullDisk() {
    ::getrlimit(RLIMIT_FSIZE, &before_);
    rlimit limit = before_;
    limit.rlim_cur = kFullAfterBytes;
    ::setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FullDisk() { ::setrlimit(RLIMIT_FSIZE, &before_); }
  FullDisk(const FullDisk&) = delete;
  FullDisk& operator=(const FullDisk&) = delete;

 private:
  rlimit before_{};
};

double variation(MainWindow& w, const char* name) { return w.scene().widgets.variation(w.scene().widgets.find(name)); }

// The names of a folder's entries, sorted (to see that no temporary file is left).
QStringList entries(const fs::path& folder) {
  QStringList names;
  for (const auto& entry : fs::directory_iterator(folder)) names << QString::fromStdString(entry.path().filename().string());
  names.sort();
  return names;
}

// The document as Save writes it: seen through the view's camera, widgets inline.
std::string savedBytes(MainWindow& w, const fs::path& scratch) {
  scenes::Scene document = w.scene();
  document.setCamera(w.sceneView().camera());
  document.widgetFile.reset();
  scenes::writeScene(scratch, document);
  const std::string bytes = slurp(scratch);
  fs::remove(scratch);
  return bytes;
}

// Types `path` into the glTF export dialog (content: the deformed meshes) and clicks OK.
ModalAnswers::Handler exportGltfTo(const fs::path& path) {
  return [path](QWidget* modal) {
    QVERIFY2(modal->objectName() == "gltfExportDialog", qPrintable(modal->objectName()));
    auto* edit = modal->findChild<QLineEdit*>("path");
    auto* buttons = modal->findChild<QDialogButtonBox*>();
    QVERIFY(edit != nullptr && buttons != nullptr);
    edit->selectAll();
    QTest::keyClicks(edit, QString::fromStdString(path.string()));
    QTest::mouseClick(buttons->button(QDialogButtonBox::Ok), Qt::LeftButton);
  };
}

// ffdkit-cli with `arguments`; on a full disk when `full`. Returns the exit code; `errors` gets
// what it wrote to stderr.
int runCli(const QStringList& arguments, bool full, QString* errors) {
  QProcess cli;
  if (full)
    cli.setChildProcessModifier([] {
      rlimit limit{};
      ::getrlimit(RLIMIT_FSIZE, &limit);
      limit.rlim_cur = kFullAfterBytes;
      ::setrlimit(RLIMIT_FSIZE, &limit);
    });
  cli.start(QString::fromStdString(ffdkit::test::ffdkitCli()), arguments);
  if (!cli.waitForFinished(120000)) return -1;
  *errors = QString::fromLocal8Bit(cli.readAllStandardError());
  return cli.exitStatus() == QProcess::NormalExit ? cli.exitCode() : -1;
}

}  // namespace

class DiskFullGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    window_ = startWindow();
    QVERIFY(window_ != nullptr);
    dir_ = std::make_unique<QTemporaryDir>();
    QVERIFY(dir_->isValid());
    folder_ = dir_->path().toStdString();
    doc_ = folder_ / "doc.json";
    fs::copy_file(kExamples / "default" / "scene.json", doc_);
    window_->openScene(doc_);
  }
  void cleanup() { closeDiscardingChanges(window_); }

  void saveOnAFullDiskKeepsTheFileAndTheEdits() {
    MainWindow& w = *window_;
    const std::string before = slurp(doc_);
    dragArrow(w, w.scene().widgets.find("pull"), 0.2);
    const double moved = variation(w, "pull");
    QString shown;
    {
      FullDisk full;
      ModalAnswers answers({readMessage(&shown, QMessageBox::Critical)});
      pressKey(w, Qt::Key_S, Qt::ControlModifier);  // File > Save Scene
      QCOMPARE(answers.answered(), 1);
    }
    QVERIFY2(shown.contains("doc.json") && shown.contains(kDiskFull), qPrintable(shown));
    QVERIFY2(shown.contains("not saved") && shown.contains("edits are still open"), qPrintable(shown));
    QCOMPARE(slurp(doc_), before);
    QCOMPARE(entries(folder_), QStringList{"doc.json"});
    QVERIFY(w.isModified());
    QCOMPARE(variation(w, "pull"), moved);
    // The app goes on: an edit, a save.
    dragArrow(w, w.scene().widgets.find("pull"), 0.1);
    const std::string expected = savedBytes(w, folder_ / "expected");
    pressKey(w, Qt::Key_S, Qt::ControlModifier);
    QVERIFY(!w.isModified());
    QCOMPARE(slurp(doc_), expected);
    QCOMPARE(entries(folder_), QStringList{"doc.json"});
  }

  // Quit, Save, and the save fails: the window stays open with the edits.
  void quitThenSaveOnAFullDiskStaysOpen() {
    MainWindow& w = *window_;
    const std::string before = slurp(doc_);
    dragArrow(w, w.scene().widgets.find("pull"), 0.2);
    QString shown;
    {
      FullDisk full;
      ModalAnswers answers({clickButton(QMessageBox::Save), readMessage(&shown, QMessageBox::Critical)});
      pressKey(w, Qt::Key_Q, Qt::ControlModifier);
      QCOMPARE(answers.answered(), 2);
    }
    QVERIFY2(shown.contains("doc.json") && shown.contains(kDiskFull) && shown.contains("not saved"), qPrintable(shown));
    QVERIFY(w.isVisible());
    QVERIFY(w.isModified());
    QCOMPARE(slurp(doc_), before);
    QCOMPARE(entries(folder_), QStringList{"doc.json"});
    QVERIFY(fs::exists(app::RecoveryFile().path()));  // the edits are still protected against a crash
  }

  void autosaveOnAFullDiskKeepsTheLastRecoveryFile() {
    MainWindow& w = *window_;
    const app::RecoveryFile recovery;
    dragArrow(w, w.scene().widgets.find("pull"), 0.2);
    QVERIFY(fs::exists(recovery.path()));
    const std::string autosaved = slurp(recovery.path());
    const QStringList recoveryFiles = entries(recovery.path().parent_path());
    {
      FullDisk full;
      dragArrow(w, w.scene().widgets.find("pull"), 0.1);  // every edit autosaves
    }
    QVERIFY2(w.statusMessage().contains("Autosave failed") && w.statusMessage().contains(kDiskFull),
             qPrintable(w.statusMessage()));
    QCOMPARE(slurp(recovery.path()), autosaved);
    QCOMPARE(entries(recovery.path().parent_path()), recoveryFiles);
    // The next edit autosaves again: the recovery file holds it.
    dragArrow(w, w.scene().widgets.find("pull"), 0.1);
    const double latest = variation(w, "pull");
    scenes::SceneReadOptions options;
    options.confinement.allowOutside = true;
    const scenes::Scene recovered = scenes::readScene(recovery.path(), options);
    QCOMPARE(recovered.widgets.variation(recovered.widgets.find("pull")), latest);
    const std::string expected = savedBytes(w, folder_ / "expected");
    pressKey(w, Qt::Key_S, Qt::ControlModifier);
    QCOMPARE(slurp(doc_), expected);
    QVERIFY(!fs::exists(recovery.path()));
  }

  // File > Export Deformed Mesh.
  void exportingADeformedMeshOnAFullDiskKeepsTheOldFile() {
    MainWindow& w = *window_;
    const fs::path mesh = folder_ / "sphere.ply";
    {
      ModalAnswers answers({chooseSavePath(mesh)});
      action(w, "actionExportMesh")->trigger();
      QCOMPARE(answers.answered(), 1);
    }
    const std::string before = slurp(mesh);
    QVERIFY(before.size() > kFullAfterBytes);
    dragArrow(w, w.scene().widgets.find("pull"), 0.2);
    QString shown;
    {
      FullDisk full;
      ModalAnswers answers({chooseSavePath(mesh, true), readMessage(&shown, QMessageBox::Critical)});
      action(w, "actionExportMesh")->trigger();
      QCOMPARE(answers.answered(), 2);
    }
    QVERIFY2(shown.contains("sphere.ply") && shown.contains(kDiskFull), qPrintable(shown));
    QCOMPARE(slurp(mesh), before);
    QCOMPARE(entries(folder_), (QStringList{"doc.json", "sphere.ply"}));
    // Again with room: the file holds the deformed points (float32 in PLY).
    {
      ModalAnswers answers({chooseSavePath(mesh, true)});
      action(w, "actionExportMesh")->trigger();
      QCOMPARE(answers.answered(), 1);
    }
    const Eigen::MatrixX3d written = meshio::readMesh(mesh).points;
    QCOMPARE(written.rows(), w.deformer().points("sphere").rows());
    QVERIFY((written - w.deformer().points("sphere")).cwiseAbs().maxCoeff() < 1e-6);
    QVERIFY(slurp(mesh) != before);
  }

  // File > Export glTF.
  void exportingGltfOnAFullDiskKeepsTheOldFile() {
    MainWindow& w = *window_;
    const fs::path glb = folder_ / "scene.glb";
    QString shown;
    {
      ModalAnswers answers({exportGltfTo(glb), readMessage(&shown, QMessageBox::Information)});
      action(w, "actionExportGltf")->trigger();
      QCOMPARE(answers.answered(), 2);
    }
    const std::string before = slurp(glb);
    QVERIFY(before.size() > kFullAfterBytes);
    dragArrow(w, w.scene().widgets.find("pull"), 0.2);
    {
      FullDisk full;
      ModalAnswers answers({exportGltfTo(glb), readMessage(&shown, QMessageBox::Critical)});
      action(w, "actionExportGltf")->trigger();
      QCOMPARE(answers.answered(), 2);
    }
    QVERIFY2(shown.contains("scene.glb") && shown.contains(kDiskFull), qPrintable(shown));
    QCOMPARE(slurp(glb), before);
    QCOMPARE(entries(folder_), (QStringList{"doc.json", "scene.glb"}));
    {
      ModalAnswers answers({exportGltfTo(glb), readMessage(&shown, QMessageBox::Information)});
      action(w, "actionExportGltf")->trigger();
      QCOMPARE(answers.answered(), 2);
    }
    QVERIFY(slurp(glb) != before);  // the edit is in it
    const std::string expected = savedBytes(w, folder_ / "expected");
    pressKey(w, Qt::Key_S, Qt::ControlModifier);
    QCOMPARE(slurp(doc_), expected);
  }

  // ffdkit-cli deform and export in a process whose disk is full: exit 1, the output as it was.
  void theCommandLineOnAFullDiskKeepsTheOldOutput_data() {
    QTest::addColumn<QStringList>("command");
    QTest::addColumn<QString>("output");
    QTest::addRow("deform") << QStringList{"deform", "--scene"} << "sphere.ply";
    QTest::addRow("export") << QStringList{"export"} << "scene.glb";
  }
  void theCommandLineOnAFullDiskKeepsTheOldOutput() {
    QFETCH(QStringList, command);
    QFETCH(QString, output);
    window_.reset();
    const fs::path out = folder_ / output.toStdString();
    const QStringList first = command + QStringList{QString::fromStdString(doc_.string()), "-o", QString::fromStdString(out.string())};
    QString errors;
    QCOMPARE(runCli(first, false, &errors), 0);
    const std::string before = slurp(out);
    QVERIFY(before.size() > kFullAfterBytes);
    const QStringList moved = first + QStringList{"--set", "pull=0.8"};
    QCOMPARE(runCli(moved, true, &errors), 1);
    QVERIFY2(errors.contains(output) && errors.contains(kDiskFull), qPrintable(errors));
    QCOMPARE(slurp(out), before);
    QCOMPARE(entries(folder_), (QStringList{"doc.json", output}));
    QCOMPARE(runCli(moved, false, &errors), 0);
    QVERIFY(slurp(out) != before);
  }

 private:
  std::unique_ptr<MainWindow> window_;
  std::unique_ptr<QTemporaryDir> dir_;  ///< a fresh folder per test
  fs::path folder_;
  fs::path doc_;
};

int main(int argc, char** argv) {
  // A write past RLIMIT_FSIZE fails with EFBIG instead of killing the process (FullDisk).
  std::signal(SIGXFSZ, SIG_IGN);
  return runGuiTest<DiskFullGuiTest>(argc, argv);
}

#include "lifecycle_disk_full_gui_test.moc"
