// The document lifecycle under a real window and real events (Xvfb): the modified flag in the
// title, Save / Discard / Cancel before Quit, Open, New and closing; Save As; New Scene, Delete
// Object and Rename (F2); widget files attached to the selected object; autosave, and after a
// SIGKILL the next start restoring the edits.
#include <QAction>
#include <QDialogButtonBox>
#include <QFileDialog>
#include <QInputDialog>
#include <QLineEdit>
#include <QFileSystemModel>
#include <QMenu>
#include <QMessageBox>
#include <QProcess>
#include <QPushButton>
#include <QSettings>
#include <QStandardPaths>
#include <QTreeWidget>
#include <QWindow>

#include <cstdio>
#include <filesystem>

#include "ffdkit/app/interaction_controller.h"
#include "ffdkit/app/recovery_file.h"
#include "ffdkit/scenes/scene_file.h"
#include "gui_test_support.h"

using namespace ffdkit;
using namespace ffdkit::app::testing;
using app::MainWindow;
using widgets::WidgetId;

namespace {

namespace fs = std::filesystem;

// The title as the window system shows it ("[*]" replaced by "*" when modified).
QString shownTitle(MainWindow& w) {
  QApplication::processEvents();
  return w.windowHandle() != nullptr ? w.windowHandle()->title() : QString();
}

// Clicks a message box's button with the mouse.
ModalAnswers::Handler clickButton(QMessageBox::StandardButton which) {
  return [which](QWidget* modal) {
    auto* box = qobject_cast<QMessageBox*>(modal);
    QVERIFY2(box != nullptr, qPrintable(modal->metaObject()->className()));
    QTest::mouseClick(box->button(which), Qt::LeftButton);
  };
}

ModalAnswers::Handler clickButtonNamed(const QString& text) {
  return [text](QWidget* modal) {
    auto* box = qobject_cast<QMessageBox*>(modal);
    QVERIFY(box != nullptr);
    for (QAbstractButton* button : box->buttons())
      if (button->text() == text) {
        QTest::mouseClick(button, Qt::LeftButton);
        return;
      }
    QFAIL(qPrintable("no button " + text));
  };
}

// Types a path into a file dialog and presses Enter.
ModalAnswers::Handler chooseFile(const fs::path& path) {
  return [path](QWidget* modal) {
    auto* dialog = qobject_cast<QFileDialog*>(modal);
    QVERIFY2(dialog != nullptr, qPrintable(modal->metaObject()->className()));
    dialog->selectFile(QString::fromStdString(path.string()));
    static_cast<QDialog*>(dialog)->accept();  // public through QDialog, virtual: QFileDialog::accept
  };
}

// Answers a Save As dialog opened on the document's own file with `path`. The dialog lists its
// folder asynchronously (QFileSystemModel's gatherer thread) and updates its selection as the
// rows arrive, which can overwrite a name chosen earlier: accept() then asked whether to replace
// the open file, a nested modal nobody answered (the test hung at random under load). So wait
// until the folder, which holds the open file, is listed; then type the new path and accept.
ModalAnswers::Handler chooseSavePath(const fs::path& path) {
  return [path](QWidget* modal) {
    auto* dialog = qobject_cast<QFileDialog*>(modal);
    QVERIFY2(dialog != nullptr, qPrintable(modal->metaObject()->className()));
    auto* files = dialog->findChild<QFileSystemModel*>();
    auto* name = dialog->findChild<QLineEdit*>("fileNameEdit");
    QVERIFY(files != nullptr && name != nullptr);
    const QModelIndex folder = files->index(QString::fromStdString(path.parent_path().string()));
    QTRY_VERIFY_WITH_TIMEOUT(files->rowCount(folder) > 0 && !files->canFetchMore(folder), 20000);
    name->selectAll();
    QTest::keyClicks(name, QString::fromStdString(path.filename().string()));
    QCOMPARE(dialog->selectedFiles(), QStringList{QString::fromStdString(path.string())});
    static_cast<QDialog*>(dialog)->accept();  // public through QDialog, virtual: QFileDialog::accept
  };
}

// Types `text` as the new name in the rename dialog and presses Enter.
ModalAnswers::Handler typeName(const QString& text) {
  return [text](QWidget* modal) {
    QVERIFY2(modal->objectName() == "renameDialog", qPrintable(modal->objectName()));
    auto* edit = modal->findChild<QLineEdit*>();
    QVERIFY(edit != nullptr);
    edit->selectAll();
    QTest::keyClicks(edit, text);
    QTest::keyClick(edit, Qt::Key_Return);
  };
}

void key(MainWindow& w, int k, Qt::KeyboardModifiers modifiers = Qt::NoModifier) {
  pressKey(w, static_cast<Qt::Key>(k), modifiers);
}

double variation(MainWindow& w, const char* name) { return w.scene().widgets.variation(w.scene().widgets.find(name)); }

// A copy of a sample scene in `dir` named `file`.
fs::path copySample(const QTemporaryDir& dir, const char* sample, const char* file) {
  const fs::path path = fs::path(dir.path().toStdString()) / file;
  fs::copy_file(kExamples / sample / "scene.json", path, fs::copy_options::overwrite_existing);
  return path;
}

// The child process of killedAppRestoresItsEditsOnTheNextStart: opens the scene, drags the
// arrow, waits for the autosave, prints the arrow's variation and waits to be killed.
int editAndWaitToBeKilled(const char* scenePath) {
  auto window = openWindow(QSize(1000, 760));
  if (!window) return 2;
  MainWindow& w = *window;
  w.openScene(scenePath);
  w.view()->grabFramebuffer();
  dragArrow(w, w.scene().widgets.find("pull"), 0.3);
  if (!w.isModified()) return 3;
  const fs::path recovery = app::RecoveryFile().path();
  if (!fs::exists(recovery)) return 4;
  std::printf("edited %.17g\n", variation(w, "pull"));
  std::fflush(stdout);
  return QApplication::exec();  // until SIGKILL
}

}  // namespace

class LifecycleGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    QSettings().clear();
    window_ = openWindow(QSize(1000, 760));
    QVERIFY(window_ != nullptr);
  }
  void cleanup() {
    if (window_ && window_->isModified()) {
      ModalAnswers discard({clickButton(QMessageBox::Discard)});
      window_->close();
    }
    window_.reset();
  }

  // ---- 1. unsaved changes -----------------------------------------------------------------

  void theTitleNamesTheFileAndMarksChanges() {
    MainWindow& w = *window_;
    QCOMPARE(shownTitle(w), QString("untitled - ffdkit"));
    const fs::path doc = copySample(dir_, "default", "doc.json");
    w.openScene(doc);
    QCOMPARE(shownTitle(w), QString("doc.json - ffdkit"));
    dragArrow(w, w.scene().widgets.find("pull"), 0.2);
    QVERIFY(w.isModified());
    QCOMPARE(shownTitle(w), QString("doc.json* - ffdkit"));
    key(w, Qt::Key_Z, Qt::ControlModifier);  // back to the saved state: not modified
    QCOMPARE(shownTitle(w), QString("doc.json - ffdkit"));
    w.openScene(kExamples / "press");
    QCOMPARE(shownTitle(w), QString("press/scene.json - ffdkit"));
  }

  void quitWithChangesAsksAndCancelKeepsEverything() {
    MainWindow& w = *window_;
    const fs::path doc = copySample(dir_, "default", "doc.json");
    const std::string bytes = slurp(doc);
    w.openScene(doc);
    dragArrow(w, w.scene().widgets.find("pull"), 0.2);
    const double moved = variation(w, "pull");
    QVERIFY(std::abs(moved - 0.7) < 0.02);
    {
      ModalAnswers answers({clickButton(QMessageBox::Cancel)});
      key(w, Qt::Key_Q, Qt::ControlModifier);  // File > Quit
      QCOMPARE(answers.answered(), 1);
    }
    QVERIFY(w.isVisible());
    QCOMPARE(variation(w, "pull"), moved);
    QVERIFY(w.isModified());
    QCOMPARE(slurp(doc), bytes);
    // Closing the window asks the same; Cancel keeps it open.
    {
      ModalAnswers answers({clickButton(QMessageBox::Cancel)});
      QVERIFY(!w.close());
      QCOMPARE(answers.answered(), 1);
    }
    QVERIFY(w.isVisible());
    QCOMPARE(variation(w, "pull"), moved);
  }

  void newSceneWithChangesAndDiscardDropsThem() {
    MainWindow& w = *window_;
    const fs::path doc = copySample(dir_, "default", "doc.json");
    const std::string bytes = slurp(doc);
    w.openScene(doc);
    dragArrow(w, w.scene().widgets.find("pull"), 0.2);
    ModalAnswers answers({clickButton(QMessageBox::Discard)});
    key(w, Qt::Key_N, Qt::ControlModifier);  // File > New Scene
    QCOMPARE(answers.answered(), 1);
    QVERIFY(w.scene().objects().empty());
    QVERIFY(w.scene().widgets.widgets().empty());
    QVERIFY(!w.isModified());
    QVERIFY(w.documentPath().empty());
    QCOMPARE(shownTitle(w), QString("untitled - ffdkit"));
    QCOMPARE(slurp(doc), bytes);
    QVERIFY(!w.commands().canUndo());
  }

  void openWithChangesAndSaveWritesThemFirst() {
    MainWindow& w = *window_;
    const fs::path doc = copySample(dir_, "default", "doc.json");
    w.openScene(doc);
    dragArrow(w, w.scene().widgets.find("pull"), 0.2);
    const double moved = variation(w, "pull");
    ModalAnswers answers({clickButton(QMessageBox::Save), chooseFile(kExamples / "mirror" / "scene.json")});
    key(w, Qt::Key_O, Qt::ControlModifier);  // File > Open Scene
    QCOMPARE(answers.answered(), 2);
    const scenes::Scene saved = scenes::readScene(doc);
    QCOMPARE(saved.widgets.variation(saved.widgets.find("pull")), moved);
    QCOMPARE(w.scene().objects().front().name, std::string("torus"));  // the mirror scene is open
    QVERIFY(!w.isModified());
  }

  void closingWithChangesAndDiscardCloses() {
    MainWindow& w = *window_;
    w.openScene(copySample(dir_, "default", "doc.json"));
    dragArrow(w, w.scene().widgets.find("pull"), 0.2);
    ModalAnswers answers({clickButton(QMessageBox::Discard)});
    QVERIFY(w.close());
    QCOMPARE(answers.answered(), 1);
    QVERIFY(!w.isVisible());
  }

  void saveAsUpdatesTheTitleAndTheRecentFiles() {
    MainWindow& w = *window_;
    w.openScene(copySample(dir_, "default", "doc.json"));
    dragArrow(w, w.scene().widgets.find("pull"), 0.2);
    const fs::path other = fs::path(dir_.path().toStdString()) / "other.json";
    ModalAnswers answers({chooseSavePath(other)});
    key(w, Qt::Key_S, Qt::ControlModifier | Qt::ShiftModifier);  // File > Save Scene As
    QCOMPARE(answers.answered(), 1);
    QVERIFY(fs::exists(other));
    QCOMPARE(shownTitle(w), QString("other.json - ffdkit"));
    QCOMPARE(w.documentPath(), other);
    const QString entry = QString::fromStdString(other.string());
    QCOMPARE(QSettings().value("recentFiles").toStringList().value(0), entry);
    QList<QAction*> recentActions;
    for (QMenu* menu : w.findChildren<QMenu*>())
      if (menu->title() == QObject::tr("Open &Recent")) recentActions = menu->actions();
    QVERIFY(!recentActions.isEmpty());
    QCOMPARE(recentActions.front()->text(), entry);
  }

  // ---- 3. New Scene, Delete Object, Rename --------------------------------------------------

  void deleteObjectTakesItsLinksInOneUndoStep() {
    MainWindow& w = *window_;
    w.openScene(kExamples / "default");
    const scenes::Scene before = w.scene();
    clickRow(w, "sphere");
    const std::size_t steps = w.commands().position();
    key(w, Qt::Key_Delete);
    QVERIFY(w.scene().objects().empty());
    QVERIFY(w.scene().attachments().empty());
    QCOMPARE(w.scene().widgets.roots().size(), std::size_t(1));  // the lattice stays
    QCOMPARE(w.commands().position(), steps + 1);
    QVERIFY(w.commands().undoDescription().find("sphere") != std::string::npos);
    key(w, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(w.scene().objects().size(), std::size_t(1));
    QCOMPARE(w.scene().attachments().size(), std::size_t(1));
    QCOMPARE(w.scene().attachments().front().objects, std::vector<std::string>{"sphere"});
    // Deformed again, as before.
    QVERIFY((w.deformer().points("sphere") - scenes::deformScene(before).at("sphere")).cwiseAbs().maxCoeff() < 1e-12);
  }

  void renameKeepsAttachmentsAndBindings() {
    MainWindow& w = *window_;
    w.openScene(kExamples / "mirror");
    const WidgetId front = w.scene().widgets.find("push-front");
    const WidgetId back = w.scene().widgets.find("push-back");
    const WidgetId lattice = w.scene().widgets.find("lattice");
    // A widget.
    clickRow(w, "push-front");
    {
      ModalAnswers answers({typeName("front")});
      key(w, Qt::Key_F2);
      QCOMPARE(answers.answered(), 1);
    }
    QCOMPARE(w.scene().widgets.name(front), std::string("front"));
    // A lattice: the attachment holds its id and needs no rewrite.
    clickRow(w, "lattice");
    {
      ModalAnswers answers({typeName("cage")});
      key(w, Qt::Key_F2);
      QCOMPARE(answers.answered(), 1);
    }
    QCOMPARE(w.scene().widgets.name(lattice), std::string("cage"));
    QVERIFY(w.scene().attachments().front().lattice == lattice);
    QCOMPARE(w.scene().widgets.name(w.scene().attachments().front().lattice), std::string("cage"));
    // An object: the attachment follows it too.
    clickRow(w, "torus");
    {
      ModalAnswers answers({typeName("ring")});
      key(w, Qt::Key_F2);
      QCOMPARE(answers.answered(), 1);
    }
    QVERIFY(w.scene().findObject("ring") != nullptr);
    QCOMPARE(w.scene().attachments().front().objects, std::vector<std::string>{"ring"});
    // The binding holds: dragging the renamed widget moves its partner; the torus deforms.
    const Eigen::MatrixX3d torus = w.deformer().points("ring");
    const double backBefore = w.scene().widgets.variation(back);
    dragArrow(w, front, 0.1);
    const double dragged = w.scene().widgets.variation(front) - 0.2;
    QVERIFY2(std::abs(dragged - 0.1) < 0.02, qPrintable(QString::number(dragged)));
    QVERIFY(std::abs(w.scene().widgets.variation(back) - backBefore - dragged) < 1e-12);
    QVERIFY((w.deformer().points("ring") - torus).cwiseAbs().maxCoeff() > 0.01);
    // Each rename is one undo step.
    key(w, Qt::Key_Z, Qt::ControlModifier);
    key(w, Qt::Key_Z, Qt::ControlModifier);
    QVERIFY(w.scene().findObject("torus") != nullptr);
    QCOMPARE(w.scene().attachments().front().objects, std::vector<std::string>{"torus"});
    // A name in use is refused with the model's message; nothing changes.
    const std::size_t steps = w.commands().position();
    clickRow(w, "front");
    {
      ModalAnswers used({typeName("cage")});
      key(w, Qt::Key_F2);
      QCOMPARE(used.answered(), 1);
    }
    QCOMPARE(w.scene().widgets.name(front), std::string("front"));
    QCOMPARE(w.commands().position(), steps);
    QVERIFY2(w.statusMessage().contains("already used"), qPrintable(w.statusMessage()));
  }

  void newSceneAsksNothingWithoutChanges() {
    MainWindow& w = *window_;
    w.openScene(kExamples / "default");
    ModalAnswers guard({clickButton(QMessageBox::Cancel)});
    action(w, "actionNewScene")->trigger();
    QCOMPARE(guard.answered(), 0);
    QVERIFY(w.scene().objects().empty());
  }

  // ---- 4. widget files ---------------------------------------------------------------------

  void aWidgetFileAttachesToTheSelectedObjectFittedAsAttachDoes() {
    MainWindow& w = *window_;
    w.openScene(kExamples / "default");
    clickRow(w, "sphere");
    ModalAnswers answers({chooseFile(FFDKIT_SOURCE_DIR "/widgets/examples/fig6-9.json")});
    action(w, "actionOpenWidgetFile")->trigger();
    QCOMPARE(answers.answered(), 1);
    QCOMPARE(w.scene().attachments().size(), std::size_t(1));
    QCOMPARE(w.scene().widgets.name(w.scene().attachments().front().lattice), std::string("parent"));
    QCOMPARE(w.scene().attachments().front().objects, std::vector<std::string>{"sphere"});
    // The parent's frame is the sphere's bounding box grown by 5 % of its diagonal per side.
    const Eigen::MatrixX3d& p = w.scene().findObject("sphere")->mesh.points;
    const Eigen::Vector3d lo = p.colwise().minCoeff(), hi = p.colwise().maxCoeff();
    const double pad = 0.05 * (hi - lo).norm();
    const Eigen::Affine3d frame = w.scene().widgets.latticeFrame(w.scene().widgets.find("parent"));
    QVERIFY((frame * Eigen::Vector3d(0, 0, 0) - (lo.array() - pad).matrix()).norm() < 1e-12);
    QVERIFY((frame * Eigen::Vector3d(1, 1, 1) - (hi.array() + pad).matrix()).norm() < 1e-12);
    QVERIFY2(w.statusMessage().contains("sphere"), qPrintable(w.statusMessage()));
    // The lift deforms the sphere.
    const Eigen::MatrixX3d before = w.deformer().points("sphere");
    dragArrow(w, w.scene().widgets.find("lift"), 0.1);
    QVERIFY((w.deformer().points("sphere") - before).cwiseAbs().maxCoeff() > 0.02);
    // One undo step took the widgets and the attachment in.
    key(w, Qt::Key_Z, Qt::ControlModifier);
    key(w, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(w.scene().widgets.name(w.scene().attachments().front().lattice), std::string("lattice"));
  }

  void aWidgetFileWithNoObjectToTakeItSaysSoAndHowToAttach() {
    MainWindow& w = *window_;
    w.openScene(kExamples / "default");
    ModalAnswers primitive({[](QWidget* dialog) { qobject_cast<QDialog*>(dialog)->accept(); }});
    action(w, "actionAddPrimitive")->trigger();  // two objects, none selected
    QCOMPARE(w.scene().objects().size(), std::size_t(2));
    clickRow(w, "lattice");  // a lattice selected, no object
    ModalAnswers answers({chooseFile(FFDKIT_SOURCE_DIR "/widgets/examples/fig6-9.json")});
    action(w, "actionOpenWidgetFile")->trigger();
    QCOMPARE(answers.answered(), 1);
    QVERIFY(w.scene().attachments().empty());
    QVERIFY2(w.statusMessage().contains("Nothing is attached") && w.statusMessage().contains("Attach Lattice to Object"),
             qPrintable(w.statusMessage()));
  }

  // ---- 2. autosave and recovery --------------------------------------------------------------

  void killedAppRestoresItsEditsOnTheNextStart() {
    window_.reset();
    const fs::path doc = copySample(dir_, "default", "doc.json");
    const std::string bytes = slurp(doc);
    QProcess child;
    child.setProcessChannelMode(QProcess::ForwardedErrorChannel);
    child.start(QCoreApplication::applicationFilePath(), {"--edit-and-wait", QString::fromStdString(doc.string())});
    QVERIFY(child.waitForStarted());
    QByteArray out;
    for (int i = 0; i < 600 && !out.contains('\n'); ++i) {
      child.waitForReadyRead(200);
      out += child.readAllStandardOutput();
      QVERIFY2(child.state() == QProcess::Running, qPrintable("child exited " + QString::number(child.exitCode())));
    }
    QVERIFY2(out.startsWith("edited "), out.constData());
    const double edited = out.mid(7).trimmed().toDouble();
    QVERIFY(std::abs(edited - 0.8) < 0.02);
    child.kill();  // SIGKILL: no close event, no cleanup
    QVERIFY(child.waitForFinished());
    QCOMPARE(child.exitStatus(), QProcess::CrashExit);
    QCOMPARE(slurp(doc), bytes);  // nothing was saved

    // The next start offers the edits; Restore brings them back, with the file's name.
    window_ = openWindow(QSize(1000, 760));
    QVERIFY(window_ != nullptr);
    MainWindow& w = *window_;
    ModalAnswers answers({clickButtonNamed(QObject::tr("Restore"))});
    QVERIFY(w.offerRecovery());
    QCOMPARE(answers.answered(), 1);
    QCOMPARE(variation(w, "pull"), edited);
    QCOMPARE(w.documentPath(), doc);
    QVERIFY(w.isModified());
    QCOMPARE(shownTitle(w), QString("doc.json* - ffdkit"));
    // The dead process's files are gone: a second start offers nothing.
    ModalAnswers guard({clickButtonNamed(QObject::tr("Discard"))});
    QVERIFY(!w.offerRecovery());
    QCOMPARE(guard.answered(), 0);
  }

  void aCleanCloseLeavesNothingToRecover() {
    MainWindow& w = *window_;
    w.openScene(copySample(dir_, "default", "doc.json"));
    dragArrow(w, w.scene().widgets.find("pull"), 0.2);
    QVERIFY(fs::exists(app::RecoveryFile().path()));
    key(w, Qt::Key_S, Qt::ControlModifier);  // saved: nothing to recover
    QVERIFY(!fs::exists(app::RecoveryFile().path()));
    dragArrow(w, w.scene().widgets.find("pull"), 0.1);
    QVERIFY(fs::exists(app::RecoveryFile().path()));
    ModalAnswers answers({clickButton(QMessageBox::Discard)});
    QVERIFY(w.close());
    QVERIFY(!fs::exists(app::RecoveryFile().path()));
  }

 private:
  std::unique_ptr<MainWindow> window_;
  QTemporaryDir dir_;
};

int main(int argc, char** argv) {
  static TemporaryUserFolders folders;
  if (argc == 3 && std::string(argv[1]) == "--edit-and-wait") {
    QSurfaceFormat::setDefaultFormat(app::VtkViewWidget::defaultFormat());
    QApplication app(argc, argv);
    return editAndWaitToBeKilled(argv[2]);
  }
  return runGuiTest<LifecycleGuiTest>(argc, argv);
}

#include "lifecycle_gui_test.moc"
