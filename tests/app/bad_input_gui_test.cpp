// Bad input through the application's own menus, with real events (Xvfb): every file of the fuzz
// corpora and their saved regressions (tests/fuzz/corpus, tests/fuzz/regressions) and the hostile
// meshes of tests/meshio/hostile_files.h, opened as a user opens them: a scene with File > Open
// Scene (Ctrl+O), a mesh with File > Import Mesh, a widget file with File > Open Widget File, the
// file dialog answered by typing the path and pressing Enter. None crashes; a file the library
// refuses is not opened and its message, naming the file, is shown; the window still undoes,
// redoes and drags afterwards. Also the read preferences: File > Read Limits... changed through
// its dialog refuses an import it allowed, recovery reads with the limits, and a scene's widget
// file or a glTF's buffer outside its folder needs File > Allow Files Outside a Scene's Folder.
#include <QDialogButtonBox>
#include <QFileDialog>
#include <QFileSystemModel>
#include <QLabel>
#include <QLineEdit>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QPushButton>
#include <QSettings>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "../meshio/hostile_files.h"
#include "ffdkit/gui/recovery_file.h"
#include "ffdkit/meshio/mesh_io.h"
#include "ffdkit/scenes/scene_file.h"
#include "ffdkit/scenes/widget_file.h"
#include "gui_test_support.h"
#include "lifecycle_dialog_answers.h"

using namespace ffdkit;
using namespace ffdkit::app::testing;
using app::MainWindow;

namespace {

namespace fs = std::filesystem;

const fs::path kFuzz = FFDKIT_SOURCE_DIR "/tests/fuzz";

/// How a file is opened, as a user opens one of its kind.
enum class OpenAs { Scene, Mesh, Widgets };

struct BadInput {
  fs::path path;
  OpenAs as = OpenAs::Scene;
  std::string expected;  ///< part of the message (hostile files), or empty
};

/// What happened while an action ran: the message boxes shown (their text, answered with OK),
/// the file dialogs and unsaved-changes prompts answered.
struct Shown {
  QStringList messages;
  int fileDialogs = 0;
  int prompts = 0;
};

/// Answers every modal the next action opens, as a user would, with real key and mouse events:
/// a file dialog gets `path` typed into its name field and Enter; the unsaved-changes prompt
/// gets Discard; any other message box is read and closed with its OK button. A modal that
/// cannot be answered so is rejected (and counted as a failure) rather than left open.
class Answerer : public QObject {
 public:
  Answerer(fs::path path, Shown& shown) : path_(std::move(path)), shown_(shown) {
    connect(&poll_, &QTimer::timeout, this, [this] { answer(); });
    poll_.start(10);
  }
  QStringList failures;

 private:
  void answer() {
    QWidget* modal = QApplication::activeModalWidget();
    if (modal == nullptr || modal->property("ffdkitAnswered").toBool()) return;
    modal->setProperty("ffdkitAnswered", true);
    if (auto* dialog = qobject_cast<QFileDialog*>(modal)) {
      ++shown_.fileDialogs;
      const QString failure = chooseFilePath(dialog, path_);
      if (!failure.isEmpty()) fail(dialog, failure.toStdString());
      return;
    }
    if (auto* box = qobject_cast<QMessageBox*>(modal)) {
      if (box->objectName() == "unsavedChangesPrompt") {
        ++shown_.prompts;
        return click(box, box->button(QMessageBox::Discard));
      }
      shown_.messages << box->text();
      return click(box, box->button(QMessageBox::Ok));
    }
    fail(modal, std::string("an unexpected ") + modal->metaObject()->className());
  }
  void click(QMessageBox* box, QAbstractButton* button) {
    if (button == nullptr) return fail(box, "a message box without the expected button");
    QTest::mouseClick(button, Qt::LeftButton);
  }
  void fail(QWidget* modal, const std::string& why) {
    failures << QString::fromStdString(why + " (" + path_.string() + ")");
    if (auto* dialog = qobject_cast<QDialog*>(modal)) dialog->reject();
  }

  fs::path path_;
  Shown& shown_;
  QTimer poll_;
};

/// Opens `path` as `as` through the window's menus (a scene by its shortcut, Ctrl+O).
Shown openThroughTheMenus(MainWindow& w, const fs::path& path, OpenAs as) {
  Shown shown;
  Answerer answerer(path, shown);
  switch (as) {
    case OpenAs::Scene: pressKey(w, Qt::Key_O, Qt::ControlModifier); break;
    case OpenAs::Mesh: clickMenuItem(w, action(w, "actionImportMesh")); break;
    case OpenAs::Widgets: clickMenuItem(w, action(w, "actionOpenWidgetFile")); break;
  }
  QApplication::processEvents();
  for (const QString& failure : answerer.failures) qWarning("%s", qPrintable(failure));
  if (!answerer.failures.isEmpty()) shown.fileDialogs = -1;  // the caller fails
  return shown;
}

/// Whether the library refuses the file with the options the app reads it with by default.
bool libraryRefuses(const fs::path& path, OpenAs as) {
  try {
    switch (as) {
      case OpenAs::Scene: (void)scenes::readScene(path, scenes::SceneReadOptions{}); break;
      case OpenAs::Mesh: (void)meshio::readMesh(path, meshio::MeshReadOptions{}); break;
      case OpenAs::Widgets: (void)scenes::readWidgetFile(path, scenes::WidgetReadOptions{}); break;
    }
    return false;
  } catch (const std::exception&) {
    return true;
  }
}

/// The fuzz inputs of one folder of tests/fuzz/corpus or tests/fuzz/regressions, by target:
/// fuzz_mesh_FORMAT files are imported as meshes (copied into `scratch` with the extension the
/// reader is picked by), fuzz_widget_file ones opened as widget files, the rest (scene files and
/// the generator fuzzer's inputs, which are not scenes) opened as scenes.
std::vector<BadInput> fuzzInputs(const fs::path& scratch) {
  std::vector<BadInput> inputs;
  for (const char* set : {"corpus", "regressions"}) {
    std::vector<fs::path> targets;
    for (const auto& entry : fs::directory_iterator(kFuzz / set))
      if (entry.is_directory()) targets.push_back(entry.path());
    std::sort(targets.begin(), targets.end());
    for (const fs::path& target : targets) {
      std::vector<fs::path> files;
      for (const auto& entry : fs::directory_iterator(target))
        if (entry.is_regular_file()) files.push_back(entry.path());
      std::sort(files.begin(), files.end());
      const std::string name = target.filename().string();
      for (const fs::path& file : files) {
        if (name.rfind("fuzz_mesh_", 0) == 0) {
          // Appended: GCC 12 warns (-Wrestrict, falsely) on "literal" + std::string&&.
          const std::string extension = std::string(".").append(name.substr(std::string("fuzz_mesh_").size()));
          const fs::path folder = scratch / set / name;
          fs::create_directories(folder);
          const fs::path copy = folder / (file.extension() == extension ? file.filename().string()
                                                                        : file.filename().string() + extension);
          fs::copy_file(file, copy, fs::copy_options::overwrite_existing);
          inputs.push_back({copy, OpenAs::Mesh, {}});
        } else {
          inputs.push_back({file, name == "fuzz_widget_file" ? OpenAs::Widgets : OpenAs::Scene, {}});
        }
      }
    }
  }
  return inputs;
}

const char* kindName(OpenAs as) {
  switch (as) {
    case OpenAs::Scene: return "scene";
    case OpenAs::Mesh: return "mesh";
    case OpenAs::Widgets: return "widget file";
  }
  return "";
}

double variation(MainWindow& w, const char* name) { return w.scene().widgets.variation(w.scene().widgets.find(name)); }

/// A text file of `count` points in the unit box.
void writeCloud(const fs::path& path, int count) {
  std::ofstream out(path);
  for (int i = 0; i < count; ++i) out << (i % 10) / 9.0 << ' ' << (i / 10 % 10) / 9.0 << ' ' << (i / 100) / 9.0 << '\n';
}

}  // namespace

class BadInputGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    // 640 x 480: Mesa draws every frame in software, in a time that goes with the pixels.
    window_ = startWindow(QSize(640, 480), StartSettings::Cleared);  // the default limits and confinement
    QVERIFY(window_ != nullptr);
  }
  void cleanup() {
    if (window_ && window_->isModified()) {
      Shown shown;
      Answerer discard({}, shown);
      window_->close();
    }
    window_.reset();
    QSettings().clear();
  }

  void readLimitsChangedInTheirDialogRefuseAnImport() {
    MainWindow& w = *window_;
    QTemporaryDir dir;
    const fs::path cloud = fs::path(dir.path().toStdString()) / "cloud.xyz";
    writeCloud(cloud, 1000);

    Shown first = openThroughTheMenus(w, cloud, OpenAs::Mesh);
    QCOMPARE(first.fileDialogs, 1);
    QVERIFY2(first.messages.isEmpty(), qPrintable(first.messages.join("\n")));
    QCOMPARE(w.scene().objects().size(), std::size_t(1));
    pressKey(w, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(w.scene().objects().size(), std::size_t(0));

    // File > Read Limits...: a malformed count is refused in the dialog, 500 is kept.
    QString problem;
    bool problemShown = false;
    ModalAnswers limits({[&](QWidget* modal) {
      QVERIFY2(modal->objectName() == "readLimitsDialog", qPrintable(modal->objectName()));
      auto* points = modal->findChild<QLineEdit*>("maxPoints");
      auto* buttons = modal->findChild<QDialogButtonBox*>();
      QVERIFY(points != nullptr && buttons != nullptr);
      QCOMPARE(points->text(), QString("50M"));
      QCOMPARE(modal->findChild<QLineEdit*>("maxMemory")->text(), QString("4G"));
      points->selectAll();
      QTest::keyClicks(points, "5x");
      QTest::mouseClick(buttons->button(QDialogButtonBox::Ok), Qt::LeftButton);
      auto* label = modal->findChild<QLabel*>("problem");
      problemShown = modal->isVisible() && label->isVisible();
      problem = label->text();
      points->selectAll();
      QTest::keyClicks(points, "500");
      QTest::mouseClick(buttons->button(QDialogButtonBox::Ok), Qt::LeftButton);
    }});
    clickMenuItem(w, action(w, "actionReadLimits"));
    QCOMPARE(limits.answered(), 1);
    QVERIFY(problemShown);
    QVERIFY2(problem.contains("'5x' is not a count"), qPrintable(problem));
    QCOMPARE(QSettings().value("readLimits/maxPoints").toULongLong(), 500ull);

    Shown refused = openThroughTheMenus(w, cloud, OpenAs::Mesh);
    QCOMPARE(refused.messages.size(), 1);
    const QString message = refused.messages.front();
    QVERIFY2(message.contains("cloud.xyz"), qPrintable(message));
    QVERIFY2(message.contains("limit of 500 points (File > Read Limits...)"), qPrintable(message));
    QCOMPARE(w.scene().objects().size(), std::size_t(0));

    // Restore Defaults in the dialog: the same file imports again.
    ModalAnswers defaults({[](QWidget* modal) {
      auto* buttons = modal->findChild<QDialogButtonBox*>();
      QVERIFY(buttons != nullptr);
      QTest::mouseClick(buttons->button(QDialogButtonBox::RestoreDefaults), Qt::LeftButton);
      QCOMPARE(modal->findChild<QLineEdit*>("maxPoints")->text(), QString("50M"));
      QTest::mouseClick(buttons->button(QDialogButtonBox::Ok), Qt::LeftButton);
    }});
    clickMenuItem(w, action(w, "actionReadLimits"));
    QCOMPARE(defaults.answered(), 1);
    Shown again = openThroughTheMenus(w, cloud, OpenAs::Mesh);
    QVERIFY2(again.messages.isEmpty(), qPrintable(again.messages.join("\n")));
    QCOMPARE(w.scene().objects().size(), std::size_t(1));
  }

  // Recovery reads the autosaved scene with the read limits (its paths are the app's own, so
  // they may lead anywhere): over them, the message says so and the file stays for another try.
  void recoveryReadsWithTheLimits() {
    MainWindow& w = *window_;
    QTemporaryDir dir;
    const fs::path cloud = fs::path(dir.path().toStdString()) / "cloud.xyz";
    writeCloud(cloud, 1000);
    // The files a killed process left: a process id that has exited.
    const pid_t gone = ::fork();
    if (gone == 0) ::_exit(0);
    QVERIFY(gone > 0);
    ::waitpid(gone, nullptr, 0);
    const fs::path folder = app::RecoveryFile::defaultDirectory();
    fs::create_directories(folder);
    const fs::path autosaved = folder / (std::to_string(gone) + ".json");
    // (No raw string here: moc's lexer takes one that ends in a quote for an open string.)
    std::ofstream(autosaved) << "{\"format\": \"ffdkit-scene\", \"version\": 1, \"objects\": [{\"name\": \"cloud\", "
                             << "\"mesh\": {\"path\": \"" << cloud.string() << "\"}}]}";
    std::ofstream(folder / (std::to_string(gone) + ".origin")) << (fs::path(dir.path().toStdString()) / "doc.json").string();

    auto restore = [](QWidget* modal) {
      auto* box = qobject_cast<QMessageBox*>(modal);
      QVERIFY(box != nullptr && box->objectName() == "recoveryPrompt");
      for (QAbstractButton* button : box->buttons())
        if (button->text() == QObject::tr("Restore")) return QTest::mouseClick(button, Qt::LeftButton);
      QFAIL("no Restore button");
    };
    QString shown;
    auto readMessage = [&shown](QWidget* modal) {
      auto* box = qobject_cast<QMessageBox*>(modal);
      QVERIFY(box != nullptr);
      shown = box->text();
      QTest::mouseClick(box->button(QMessageBox::Ok), Qt::LeftButton);
    };
    QSettings().setValue("readLimits/maxPoints", 500);
    {
      ModalAnswers answers({restore, readMessage});
      QVERIFY(!w.offerRecovery());
      QCOMPARE(answers.answered(), 2);
    }
    QVERIFY2(shown.contains("cloud.xyz"), qPrintable(shown));
    QVERIFY2(shown.contains("limit of 500 points (File > Read Limits...)"), qPrintable(shown));
    QVERIFY(fs::exists(autosaved));  // for another try
    QVERIFY(w.scene().objects().empty());

    QSettings().remove("readLimits/maxPoints");
    {
      ModalAnswers answers({restore});
      QVERIFY(w.offerRecovery());
      QCOMPARE(answers.answered(), 1);
    }
    QCOMPARE(w.scene().objects().size(), std::size_t(1));
    QCOMPARE(w.scene().objects().front().mesh.points.rows(), Eigen::Index(1000));
    QVERIFY(!fs::exists(autosaved));
  }

  // One preference for every path a file names: a scene's widget file, a glTF's buffer.
  void filesOutsideTheirFolderNeedThePreference() {
    MainWindow& w = *window_;
    QTemporaryDir dir;
    const fs::path root = dir.path().toStdString();
    fs::create_directories(root / "shared");
    fs::copy_file(fs::path(FFDKIT_SOURCE_DIR) / "widgets" / "examples" / "fig6-8.json", root / "tool.json");
    std::ofstream(root / "shared" / "scene.json") << R"({"format": "ffdkit-scene", "version": 1, "objects": [], "widgetFile": "../tool.json"})";
    std::string triangle;
    for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) triangle.append(reinterpret_cast<const char*>(&v), sizeof v);
    std::ofstream(root / "triangle.bin", std::ios::binary) << triangle;
    std::ofstream(root / "shared" / "triangle.gltf") << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}], "buffers": [{"byteLength": 36, "uri": "../triangle.bin"}]})";

    Shown refusedMesh = openThroughTheMenus(w, root / "shared" / "triangle.gltf", OpenAs::Mesh);
    QCOMPARE(refusedMesh.messages.size(), 1);
    QVERIFY2(refusedMesh.messages.front().contains("triangle.gltf"), qPrintable(refusedMesh.messages.front()));
    QVERIFY2(refusedMesh.messages.front().contains("'../triangle.bin' is outside the"), qPrintable(refusedMesh.messages.front()));
    QCOMPARE(w.scene().objects().size(), std::size_t(0));

    Shown refused = openThroughTheMenus(w, root / "shared" / "scene.json", OpenAs::Scene);
    QCOMPARE(refused.messages.size(), 1);
    const QString message = refused.messages.front();
    QVERIFY2(message.contains("'../tool.json' is outside the"), qPrintable(message));
    QVERIFY2(message.contains("scene.json"), qPrintable(message));
    QVERIFY2(message.contains("File > Allow Files Outside a Scene's Folder"), qPrintable(message));
    QVERIFY2(!message.contains("ffdkit-widgets"), qPrintable(message));  // never the other file's text
    QVERIFY(w.documentPath().empty());

    QAction* allow = action(w, "actionAllowOutside");
    QVERIFY(!allow->isChecked());
    clickMenuItem(w, allow);
    QTRY_VERIFY(allow->isChecked());
    Shown opened = openThroughTheMenus(w, root / "shared" / "scene.json", OpenAs::Scene);
    QVERIFY2(opened.messages.isEmpty(), qPrintable(opened.messages.join("\n")));
    QCOMPARE(w.documentPath(), root / "shared" / "scene.json");
    QVERIFY(!w.scene().widgets.roots().empty());
    Shown imported = openThroughTheMenus(w, root / "shared" / "triangle.gltf", OpenAs::Mesh);
    QVERIFY2(imported.messages.isEmpty(), qPrintable(imported.messages.join("\n")));
    QCOMPARE(w.scene().objects().size(), std::size_t(1));
    QCOMPARE(w.scene().objects().front().mesh.points.rows(), Eigen::Index(3));
  }

  void everyBadInputOpensWithAMessageOrNotAtAllAndTheWindowStillWorks() {
    MainWindow& w = *window_;
    QTemporaryDir dir;
    const fs::path scratch = dir.path().toStdString();
    std::vector<BadInput> inputs = fuzzInputs(scratch);
    QVERIFY(inputs.size() > 50);
    fs::create_directories(scratch / "hostile");
    for (const auto& file : meshio::test::hostileFiles()) {
      std::ofstream(scratch / "hostile" / file.name, std::ios::binary) << file.bytes;
      inputs.push_back({scratch / "hostile" / file.name, OpenAs::Mesh, file.expected});
    }
    int opened = 0, refused = 0;
    for (const BadInput& input : inputs) {
      const QString name = QString::fromStdString(input.path.filename().string());
      const bool error = libraryRefuses(input.path, input.as);
      const std::size_t objects = w.scene().objects().size();
      const std::size_t widgetCount = w.scene().widgets.roots().size();
      const fs::path document = w.documentPath();
      const Shown shown = openThroughTheMenus(w, input.path, input.as);
      const QString what = QString("%1 as a %2: ").arg(name, kindName(input.as));
      QVERIFY2(shown.fileDialogs == 1, qPrintable(what + "the file dialog was not answered"));
      QVERIFY2(shown.messages.size() <= 1, qPrintable(what + shown.messages.join("\n")));
      const bool messageShown = shown.messages.size() == 1;
      if (messageShown) {
        ++refused;
        QVERIFY2(shown.messages.front().contains(name), qPrintable(what + "the message does not name the file: " +
                                                                   shown.messages.front()));
        if (!input.expected.empty())
          QVERIFY2(shown.messages.front().contains(QString::fromStdString(input.expected)),
                   qPrintable(what + shown.messages.front()));
        if (!error) qInfo("%s", qPrintable(what + "the library reads it; the app refused it: " + shown.messages.front()));
        // Nothing of a refused file came in.
        QCOMPARE(w.scene().objects().size(), objects);
        QCOMPARE(w.scene().widgets.roots().size(), widgetCount);
        QCOMPARE(w.documentPath(), document);
      } else {
        QVERIFY2(!error, qPrintable(what + "the library refuses it, the app showed nothing"));
        ++opened;
        if (input.as == OpenAs::Scene) QCOMPARE(w.documentPath(), input.path);
        if (input.as == OpenAs::Mesh) QCOMPARE(w.scene().objects().size(), objects + 1);
      }
      // The window still works: undo and redo what came in (nothing, after a refusal or a scene),
      // then undo it again, leaving the document unmodified for the next file.
      if (w.isModified()) {
        const std::size_t after = w.scene().objects().size();
        pressKey(w, Qt::Key_Z, Qt::ControlModifier);
        QCOMPARE(w.scene().objects().size(), objects);
        pressKey(w, Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);
        QCOMPARE(w.scene().objects().size(), after);
        pressKey(w, Qt::Key_Z, Qt::ControlModifier);
        QVERIFY2(!w.isModified(), qPrintable(what + "still modified after undo"));
      }
      w.view()->grabFramebuffer();  // and draws
    }
    qInfo("%zu inputs: %d opened, %d refused with a message naming the file", inputs.size(), opened, refused);
    QVERIFY(refused > 0);

    // A drag after all of them: the sample scene's translate widget follows and undoes.
    const fs::path sample = scratch / "default.json";
    fs::copy_file(kExamples / "default" / "scene.json", sample);
    Shown shown = openThroughTheMenus(w, sample, OpenAs::Scene);
    QVERIFY2(shown.messages.isEmpty(), qPrintable(shown.messages.join("\n")));
    const double before = variation(w, "pull");
    dragArrow(w, w.scene().widgets.find("pull"), 0.2);
    QVERIFY(std::abs(variation(w, "pull") - before) > 0.05);
    pressKey(w, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(variation(w, "pull"), before);
  }

 private:
  std::unique_ptr<MainWindow> window_;
};

int main(int argc, char** argv) { return runGuiTest<BadInputGuiTest>(argc, argv); }

#include "bad_input_gui_test.moc"
