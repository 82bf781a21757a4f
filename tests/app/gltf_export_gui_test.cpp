// File > Export glTF... under a real window and real events (Xvfb): the options dialog driven
// with keys and clicks, the file it writes compared byte for byte with the library's export of
// the same scene and options, the report shown; a skin over its tolerance refused with the
// numbers and nothing written.
#include <QAction>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QLineEdit>
#include <QMessageBox>
#include <QPushButton>
#include <QTemporaryDir>

#include <filesystem>
#include <sstream>

#include "ffdkit/exporters/gltf_export.h"
#include "ffdkit/exporters/scene_animation.h"
#include "gui_test_support.h"

using namespace ffdkit;
using namespace ffdkit::app::testing;
using app::MainWindow;

namespace {

namespace fs = std::filesystem;

// Fills the export dialog as a user does: Down in the content box `contentDowns` times (0 frame,
// 2 skin), Down in the joints box for 8, the tolerance and the path typed, OK clicked.
ModalAnswers::Handler fillDialog(int contentDowns, bool eightJoints, const QString& tolerance, const fs::path& path) {
  return [=](QWidget* modal) {
    QVERIFY2(modal->objectName() == "gltfExportDialog", qPrintable(modal->objectName()));
    auto* content = modal->findChild<QComboBox*>("content");
    auto* joints = modal->findChild<QComboBox*>("joints");
    auto* spin = modal->findChild<QDoubleSpinBox*>("tolerance");
    auto* edit = modal->findChild<QLineEdit*>("path");
    QVERIFY(content && joints && spin && edit);
    for (int i = 0; i < contentDowns; ++i) QTest::keyClick(content, Qt::Key_Down);
    QCOMPARE(joints->isEnabled(), contentDowns == 2);
    if (eightJoints) QTest::keyClick(joints, Qt::Key_Down);
    if (!tolerance.isEmpty()) {
      spin->selectAll();
      QTest::keyClicks(spin, tolerance);
    }
    QTest::keyClicks(edit, QString::fromStdString(path.string()));
    auto* buttons = modal->findChild<QDialogButtonBox*>();
    QVERIFY(buttons != nullptr);
    QTest::mouseClick(buttons->button(QDialogButtonBox::Ok), Qt::LeftButton);
  };
}

// Reads the message box's text into `text` and clicks OK.
ModalAnswers::Handler readBox(QString* text, QMessageBox::Icon icon) {
  return [=](QWidget* modal) {
    auto* box = qobject_cast<QMessageBox*>(modal);
    QVERIFY2(box != nullptr, qPrintable(modal->metaObject()->className()));
    QCOMPARE(box->icon(), icon);
    *text = box->text();
    QTest::mouseClick(box->button(QMessageBox::Ok), Qt::LeftButton);
  };
}

}  // namespace

class GltfExportGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    window_ = startWindow(QSize(1000, 760), StartSettings::Kept, kExamples / "press");
    QVERIFY(window_ != nullptr);
  }
  void cleanup() { window_.reset(); }

  void aSkinWrittenFromTheDialogIsTheLibrarysExport() {
    QTemporaryDir dir;
    const fs::path path = fs::path(dir.path().toStdString()) / "press.glb";
    QString shown;
    {
      ModalAnswers answers({fillDialog(2, true, "0.0001", path), readBox(&shown, QMessageBox::Information)});
      action(*window_, "actionExportGltf")->trigger();
      QTRY_COMPARE(answers.answered(), 2);
    }
    QVERIFY2(shown.contains("9 joints, 8 per vertex"), qPrintable(shown));
    QVERIFY(fs::exists(path));
    exporters::GltfExportOptions options;
    options.content = exporters::GltfContent::Skin;
    options.joints = 8;
    options.raiseJoints = false;
    options.tolerance = 1e-4;
    std::ostringstream expected(std::ios::binary);
    exporters::exportGltf(window_->scene(), exporters::sceneAnimation(window_->scene()), expected, options);
    QVERIFY(slurp(path) == expected.str());
  }

  void aSkinOverItsToleranceIsRefusedWithTheNumbersAndNothingIsWritten() {
    QTemporaryDir dir;
    const fs::path path = fs::path(dir.path().toStdString()) / "refused.glb";
    QString shown;
    {
      // 4 joints (raised to 8 if needed): press needs 8 below 0.03, and 8 give 1.5e-7 > 1e-9.
      ModalAnswers answers({fillDialog(2, false, "0.000000001", path), readBox(&shown, QMessageBox::Critical)});
      action(*window_, "actionExportGltf")->trigger();
      QTRY_COMPARE(answers.answered(), 2);
    }
    QVERIFY2(shown.contains("refused") && shown.contains("with 8"), qPrintable(shown));
    QVERIFY(!fs::exists(path));
  }

  void theDeformedMeshesAsShown() {
    QTemporaryDir dir;
    const fs::path path = fs::path(dir.path().toStdString()) / "frame.glb";
    QString shown;
    {
      ModalAnswers answers({fillDialog(0, false, "", path), readBox(&shown, QMessageBox::Information)});
      action(*window_, "actionExportGltf")->trigger();
      QTRY_COMPARE(answers.answered(), 2);
    }
    std::ostringstream expected(std::ios::binary);
    exporters::exportGltf(window_->scene(), {}, expected, {});
    QVERIFY(slurp(path) == expected.str());
  }

 private:
  std::unique_ptr<MainWindow> window_;
};

int main(int argc, char** argv) { return runGuiTest<GltfExportGuiTest>(argc, argv); }

#include "gltf_export_gui_test.moc"
