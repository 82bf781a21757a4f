// The document lifecycle under a real window and real events (Xvfb): the modified flag in the
// title; Save / Discard / Cancel before Quit, Open, New and the window manager's close; Save As;
// New Scene, Delete Object and Rename (F2); widget files attached to the selected object;
// autosave, and the real application, killed with SIGKILL, offering the edits when started again.
#include <QAction>
#include <QDialogButtonBox>
#include <QElapsedTimer>
#include <QFileDialog>
#include <QInputDialog>
#include <QLineEdit>
#include <QMenu>
#include <QMessageBox>
#include <QProcess>
#include <QPushButton>
#include <QSettings>
#include <QTreeWidget>
#include <QWindow>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <utility>

#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/gui/recovery_file.h"
#include "ffdkit/scenes/scene_file.h"
#include "gui_test_support.h"
#include "lifecycle_dialog_answers.h"
#include "lifecycle_window_manager.h"

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

constexpr std::uint32_t kKeyReturn = 0xff0d;  // X11 keysyms (keysymdef.h)
constexpr std::uint32_t kKeyDelete = 0xffff;

// The close button of the window's frame: the window manager's WM_DELETE_WINDOW message,
// through the X server, to the window (not a call of close()).
void closeFromWindowManager(MainWindow& w) {
  WindowManager manager;
  QVERIFY2(manager.connected(), "no X server at $DISPLAY");
  const auto window = WindowManager::Window(w.winId());
  QVERIFY(manager.takesDeleteWindow(window));
  manager.requestClose(window);
}

// The shown window of process `pid` titled `title`, once it appears (within `ms`).
std::optional<WindowManager::Window> waitForWindow(WindowManager& manager, qint64 pid, const std::string& title,
                                                   int ms = 60000) {
  QElapsedTimer clock;
  clock.start();
  while (clock.elapsed() < ms) {
    if (const auto window = manager.findWindow(pid, title)) return window;
    QTest::qWait(50);
  }
  std::string shown;
  for (WindowManager::Window window : manager.windowsOf(pid)) shown += " '" + manager.title(window) + "'";
  qWarning("no window '%s' of process %lld; it shows:%s", title.c_str(), static_cast<long long>(pid), shown.c_str());
  return std::nullopt;
}

// Gives the window the keyboard focus (as a window manager does when it is clicked) and types a
// key into it.
void typeInto(WindowManager& manager, WindowManager::Window window, std::uint32_t keysym, std::uint16_t modifiers = 0) {
  manager.focus(window);
  QTRY_COMPARE(manager.focused(), window);
  QVERIFY(manager.typeKey(window, keysym, modifiers));
}

// The application's recovery folder under the test's XDG_DATA_HOME (RecoveryFile's default
// directory as the app, named "ffdkit", finds it).
fs::path appRecoveryFolder() { return fs::path(qEnvironmentVariable("XDG_DATA_HOME").toStdString()) / "ffdkit" / "recovery"; }

bool hasWidget(const scenes::Scene& scene, const std::string& name) {
  for (WidgetId id : scene.widgets.widgets())
    if (scene.widgets.name(id) == name) return true;
  return false;
}

// The names of a folder's entries, sorted (to see that no temporary file is left).
QStringList entries(const fs::path& folder) {
  QStringList names;
  for (const auto& entry : fs::directory_iterator(folder)) names << QString::fromStdString(entry.path().filename().string());
  names.sort();
  return names;
}
}  // namespace

class LifecycleGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    // 640 x 480: Mesa draws every frame in software, in a time that goes with the pixels.
    window_ = startWindow(QSize(640, 480), StartSettings::Cleared);
    QVERIFY(window_ != nullptr);
  }
  void cleanup() { closeDiscardingChanges(window_); }

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

  // Save / Discard / Cancel before each of the four ways to leave a document with unsaved
  // changes: Quit (Ctrl+Q), Open (Ctrl+O, its file dialog answered), New (Ctrl+N) and the window
  // manager closing the window (a WM_DELETE_WINDOW message through the X server).
  void unsavedChangesPrompt_data() {
    QTest::addColumn<QString>("leave");
    QTest::addColumn<int>("answer");
    const std::pair<const char*, QMessageBox::StandardButton> answers[] = {
        {"save", QMessageBox::Save}, {"discard", QMessageBox::Discard}, {"cancel", QMessageBox::Cancel}};
    for (const char* leave : {"quit", "open", "new", "windowManagerClose"})
      for (const auto& [name, button] : answers)
        QTest::newRow(qPrintable(QString("%1/%2").arg(leave, name))) << QString(leave) << int(button);
  }

  // Save: the file holds the edits, byte for byte as writeScene writes the document, and the
  // action goes on. Discard: the file untouched, the action goes on. Cancel: nothing changes.
  void unsavedChangesPrompt() {
    QFETCH(QString, leave);
    QFETCH(int, answer);
    const auto button = QMessageBox::StandardButton(answer);
    MainWindow& w = *window_;
    const QTemporaryDir dir;
    const fs::path folder = dir.path().toStdString();
    const fs::path doc = copySample(dir, "default", "doc.json");
    const std::string before = slurp(doc);
    w.openScene(doc);
    dragArrow(w, w.scene().widgets.find("pull"), 0.2);
    const double moved = variation(w, "pull");
    QVERIFY(std::abs(moved - 0.2) < 0.02);  // from the file's 0 (it stores frame 0, the rest pose)
    QVERIFY(w.isModified());
    // What Save must write: the document seen through the view's camera, widgets inline.
    scenes::Scene document = w.scene();
    document.setCamera(w.sceneView().camera());
    document.widgetFile.reset();
    const fs::path reference = folder / "reference" / "doc.json";
    fs::create_directories(reference.parent_path());
    scenes::writeScene(reference, document);
    const std::string edited = slurp(reference);
    QVERIFY(edited != before);

    const fs::path other = kExamples / "mirror" / "scene.json";
    std::vector<ModalAnswers::Handler> handlers{clickButton(button)};
    if (leave == "open" && button != QMessageBox::Cancel) handlers.push_back(chooseFile(other));
    const int dialogs = int(handlers.size());
    ModalAnswers answers(std::move(handlers));
    if (leave == "quit") {
      key(w, Qt::Key_Q, Qt::ControlModifier);
    } else if (leave == "open") {
      key(w, Qt::Key_O, Qt::ControlModifier);
    } else if (leave == "new") {
      key(w, Qt::Key_N, Qt::ControlModifier);
    } else {
      closeFromWindowManager(w);
      if (QTest::currentTestFailed()) return;
    }
    QTRY_VERIFY2_WITH_TIMEOUT(answers.answered() == dialogs,
                              qPrintable(QString("%1 of %2 dialogs answered; the window is %3, %4")
                                             .arg(answers.answered()).arg(dialogs)
                                             .arg(w.isVisible() ? "shown" : "hidden")
                                             .arg(w.isModified() ? "modified" : "not modified")),
                              20000);
    const bool closes = leave == "quit" || leave == "windowManagerClose";
    if (closes && button != QMessageBox::Cancel) QTRY_VERIFY_WITH_TIMEOUT(!w.isVisible(), 10000);
    QTest::qWait(50);  // anything still queued (the window system's close) is handled
    QCOMPARE(slurp(doc), button == QMessageBox::Save ? edited : before);
    QCOMPARE(entries(folder), (QStringList{"doc.json", "reference"}));  // no temporary left

    if (button == QMessageBox::Cancel) {
      QVERIFY(w.isVisible());
      QVERIFY(w.isModified());
      QCOMPARE(variation(w, "pull"), moved);
      QCOMPARE(w.documentPath(), doc);
      QCOMPARE(shownTitle(w), QString("doc.json* - ffdkit"));
      QVERIFY(fs::exists(app::RecoveryFile().path()));  // still protected against a crash
      return;
    }
    if (closes) {
      QVERIFY(!w.isVisible());
      QVERIFY(!fs::exists(app::RecoveryFile().path()));  // closed properly: nothing to recover
    } else if (leave == "open") {
      QCOMPARE(w.documentPath(), other);
      QCOMPARE(w.scene().objects().front().name, std::string("torus"));
      QVERIFY(!w.isModified());
    } else {
      QVERIFY(w.scene().objects().empty());
      QVERIFY(w.scene().widgets.widgets().empty());
      QVERIFY(w.documentPath().empty());
      QCOMPARE(shownTitle(w), QString("untitled - ffdkit"));
      QVERIFY(!w.isModified());
      QVERIFY(!w.commands().canUndo());
    }
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
    QVERIFY(w.scene().attachments().front().objects == std::vector<scenes::ObjectId>{w.scene().objectId("sphere")});
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
    QVERIFY(w.scene().attachments().front().objects == std::vector<scenes::ObjectId>{w.scene().objectId("ring")});
    // The binding holds: dragging the renamed widget moves its partner; the torus deforms.
    const Eigen::MatrixX3d torus = w.deformer().points("ring");
    const double backBefore = w.scene().widgets.variation(back), frontBefore = w.scene().widgets.variation(front);
    dragArrow(w, front, 0.1);
    const double dragged = w.scene().widgets.variation(front) - frontBefore;
    QVERIFY2(std::abs(dragged - 0.1) < 0.02, qPrintable(QString::number(dragged)));
    QVERIFY(std::abs(w.scene().widgets.variation(back) - backBefore - dragged) < 1e-12);
    QVERIFY((w.deformer().points("ring") - torus).cwiseAbs().maxCoeff() > 0.01);
    // Each rename is one undo step.
    key(w, Qt::Key_Z, Qt::ControlModifier);
    key(w, Qt::Key_Z, Qt::ControlModifier);
    QVERIFY(w.scene().findObject("torus") != nullptr);
    QVERIFY(w.scene().attachments().front().objects == std::vector<scenes::ObjectId>{w.scene().objectId("torus")});
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
    QVERIFY(w.scene().attachments().front().objects == std::vector<scenes::ObjectId>{w.scene().objectId("sphere")});
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

  // The real application, started twice: the first run deletes a widget with the Delete key and
  // is killed (SIGKILL) after its autosave; the second run, started as a user starts it (no
  // arguments), offers the edits from main(); Return takes the prompt's default, Restore; Ctrl+S
  // saves the restored document to its own file; Ctrl+Q quits cleanly.
  void aKilledAppOffersItsEditsWhenStartedAgain() {
    window_.reset();
    WindowManager manager;
    QVERIFY2(manager.connected(), "no X server at $DISPLAY");
    const fs::path doc = copySample(dir_, "default", "doc.json");
    const std::string bytes = slurp(doc);
    const scenes::Scene original = scenes::readScene(doc);
    QVERIFY(hasWidget(original, "pull"));

    QProcess first;
    first.setProcessChannelMode(QProcess::ForwardedChannels);
    first.start(FFDKIT_APP, {QString::fromStdString(doc.string()), "--select", "pull"});
    QVERIFY(first.waitForStarted());
    const auto firstWindow = waitForWindow(manager, first.processId(), "doc.json - ffdkit");
    QVERIFY(firstWindow.has_value());
    typeInto(manager, *firstWindow, kKeyDelete);  // deletes the selected widget
    QTRY_COMPARE_WITH_TIMEOUT(manager.title(*firstWindow), std::string("doc.json* - ffdkit"), 20000);
    const fs::path autosaved = appRecoveryFolder() / (std::to_string(first.processId()) + ".json");
    QTRY_VERIFY_WITH_TIMEOUT(fs::exists(autosaved), 20000);
    first.kill();  // SIGKILL: no close event, no cleanup
    QVERIFY(first.waitForFinished());
    QCOMPARE(first.exitStatus(), QProcess::CrashExit);
    QCOMPARE(slurp(doc), bytes);  // nothing was saved
    QVERIFY(fs::exists(autosaved));

    QProcess second;
    second.setProcessChannelMode(QProcess::ForwardedChannels);
    second.start(FFDKIT_APP, {});
    QVERIFY(second.waitForStarted());
    const auto prompt = waitForWindow(manager, second.processId(), "Recover unsaved changes");
    QVERIFY(prompt.has_value());
    typeInto(manager, *prompt, kKeyReturn);  // Restore
    // The restored document: its own file's name, modified.
    const auto secondWindow = waitForWindow(manager, second.processId(), "doc.json* - ffdkit", 20000);
    QVERIFY(secondWindow.has_value());
    typeInto(manager, *secondWindow, 's', XCB_MOD_MASK_CONTROL);
    QTRY_COMPARE_WITH_TIMEOUT(manager.title(*secondWindow), std::string("doc.json - ffdkit"), 20000);
    // The file holds the edit: the sample's widgets but the deleted one.
    const scenes::Scene saved = scenes::readScene(doc);
    QVERIFY(!hasWidget(saved, "pull"));
    QCOMPARE(saved.widgets.widgets().size(), original.widgets.widgets().size() - 1);
    QCOMPARE(saved.objects().size(), original.objects().size());
    typeInto(manager, *secondWindow, 'q', XCB_MOD_MASK_CONTROL);
    QVERIFY(second.waitForFinished(20000));
    QCOMPARE(second.exitStatus(), QProcess::NormalExit);
    QCOMPARE(second.exitCode(), 0);
    // The killed run's files went with the restore, the second run's with its clean exit.
    QCOMPARE(entries(appRecoveryFolder()), QStringList());
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

int main(int argc, char** argv) { return runGuiTest<LifecycleGuiTest>(argc, argv); }

#include "lifecycle_gui_test.moc"
