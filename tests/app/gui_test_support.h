#pragma once

// Real Qt events for the GUI tests (Xvfb): mouse events sent to the application's 3D view,
// world points mapped to the view's pixels, and a main() that sets VTK's surface format first.

#include <QAction>
#include <QApplication>
#include <QFile>
#include <QElapsedTimer>
#include <QMenu>
#include <QMenuBar>
#include <QMouseEvent>
#include <QPointer>
#include <QSettings>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QTest>
#include <QTimer>
#include <QTreeWidget>

#include <deque>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>

#include <cmath>
#include <memory>

#include <Eigen/Core>

#include "ffdkit/gui/main_window.h"
#include "ffdkit/render/scene_view.h"
#include "ffdkit/viewhost/vtk_view_widget.h"

namespace ffdkit::app::testing {

/// The sample scenes of the source tree (FFDKIT_SOURCE_DIR: ffdkit_add_qt_test defines it).
inline const std::filesystem::path kExamples = FFDKIT_SOURCE_DIR "/scenes/examples";

/// A file's bytes.
inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

inline void sendMouse(QWidget* widget, QEvent::Type type, QPoint at, Qt::MouseButton button, Qt::MouseButtons buttons,
                      Qt::KeyboardModifiers modifiers = Qt::NoModifier) {
  QMouseEvent event(type, QPointF(at), widget->mapToGlobal(QPointF(at)), button, buttons, modifiers);
  QApplication::sendEvent(widget, &event);
}

/// Where the view draws world point p, in the view widget's (logical) coordinates.
inline QPoint toWidget(MainWindow& w, const Eigen::Vector3d& p) {
  const Eigen::Vector2d d = w.sceneView().displayPoint(p);
  const double ratio = w.view()->devicePixelRatioF();
  return QPoint(static_cast<int>(std::lround(d.x() / ratio)),
                static_cast<int>(std::lround((w.view()->height() * ratio - 1.0 - d.y()) / ratio)));
}

inline void click(MainWindow& w, QPoint at, Qt::KeyboardModifiers modifiers = Qt::NoModifier) {
  sendMouse(w.view(), QEvent::MouseButtonPress, at, Qt::LeftButton, Qt::LeftButton, modifiers);
  sendMouse(w.view(), QEvent::MouseButtonRelease, at, Qt::LeftButton, Qt::NoButton, modifiers);
}

/// The pointer moves over the view with no button down.
inline void hover(MainWindow& w, QPoint at) { sendMouse(w.view(), QEvent::MouseMove, at, Qt::NoButton, Qt::NoButton); }

/// A left-button drag in the view from pixel a to pixel b in ten moves.
inline void dragPixels(MainWindow& w, QPoint a, QPoint b) {
  sendMouse(w.view(), QEvent::MouseButtonPress, a, Qt::LeftButton, Qt::LeftButton);
  for (int step = 1; step <= 10; ++step)
    sendMouse(w.view(), QEvent::MouseMove, a + (b - a) * step / 10, Qt::NoButton, Qt::LeftButton);
  sendMouse(w.view(), QEvent::MouseButtonRelease, b, Qt::LeftButton, Qt::NoButton);
}

/// A left-button drag from where world point `from` is drawn to where `to` is.
inline void dragWorld(MainWindow& w, const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  dragPixels(w, toWidget(w, from), toWidget(w, to));
}

/// Drags a translate widget's arrow `distance` world units along its axis.
inline void dragArrow(MainWindow& w, widgets::WidgetId affine, double distance) {
  const widgets::WidgetFrame f = w.scene().widgets.affineFrame(affine);
  const Eigen::Vector3d x = f.frame.linear().col(0);
  const Eigen::Vector3d grab = f.frame.translation() + 0.6 * f.size * x;
  dragWorld(w, grab, grab + distance * x);
}

/// Makes `w` the active window, as a click on it would: Qt gives window shortcuts, menus and
/// tooltips only to the active window.
inline void activate(QWidget& w) {
  if (QApplication::activeWindow() == &w) return;
  w.activateWindow();
#if QT_VERSION < QT_VERSION_CHECK(6, 5, 0)
  // Another test's window on the same display (CTest runs GUI tests in parallel in one Xvfb)
  // may hold the X focus: make this one Qt's active window regardless.
  QApplication::setActiveWindow(&w);
#endif
  if (!QTest::qWaitForWindowActive(&w)) qWarning("the window did not become active");
}

/// A key pressed (and released) on the 3D view of the active window, as a user types it:
/// window shortcuts (menu actions) get it first. The window is activated first.
inline void pressKey(MainWindow& w, Qt::Key key, Qt::KeyboardModifiers modifiers = Qt::NoModifier) {
  activate(w);
  w.view()->setFocus();
  QTest::keyClick(w.view(), key, modifiers);
}

/// Clicks the menu bar's title of the menu that holds `item`, then `item` in the open menu, with
/// the mouse, as a user does.
inline void clickMenuItem(MainWindow& w, QAction* item) {
  QMenu* menu = nullptr;
  QAction* title = nullptr;
  for (QAction* a : w.menuBar()->actions())
    if (a->menu() != nullptr && a->menu()->actions().contains(item)) title = a, menu = a->menu();
  QVERIFY2(menu != nullptr, qPrintable(item->objectName()));
  activate(w);
  QTest::mouseClick(w.menuBar(), Qt::LeftButton, Qt::NoModifier, w.menuBar()->actionGeometry(title).center());
  QTRY_VERIFY(menu->isVisible());
  QTest::mouseClick(menu, Qt::LeftButton, Qt::NoModifier, menu->actionGeometry(item).center());
}

/// The window's action of that object name (fatal if there is none).
inline QAction* action(MainWindow& w, const char* name) {
  auto* a = w.findChild<QAction*>(name);
  if (a == nullptr) qFatal("no action %s", name);
  return a;
}

/// Clicks the outliner row named `text` (with modifiers, e.g. Ctrl to extend the selection);
/// for a lattice, its own row, not the one under each object it deforms.
inline void clickRow(MainWindow& w, const QString& text, Qt::KeyboardModifiers modifiers = Qt::NoModifier) {
  QTreeWidget* tree = w.outliner();
  for (QTreeWidgetItem* item : tree->findItems(text, Qt::MatchExactly | Qt::MatchRecursive)) {
    if (item->text(1) == QObject::tr("deformed by")) continue;
    tree->scrollToItem(item);
    QTest::mouseClick(tree->viewport(), Qt::LeftButton, modifiers, tree->visualItemRect(item).center());
    return;
  }
  QFAIL(qPrintable("no outliner row " + text));
}

/// A shown main window of `size` (if given), exposed, with a first frame drawn (which sizes
/// VTK's window); null if the window system never exposed it.
inline std::unique_ptr<MainWindow> openWindow(QSize size = QSize()) {
  auto window = std::make_unique<MainWindow>();
  if (size.isValid()) window->resize(size);
  window->show();
  if (!QTest::qWaitForWindowExposed(window.get())) return nullptr;
  window->view()->grabFramebuffer();
  return window;
}

/// Whether a test function starts from the default settings (startWindow).
enum class StartSettings {
  Kept,    ///< the settings the previous test function left
  Cleared  ///< QSettings().clear() first: default limits, layout, recent files
};

/// The window a test function runs in (its init() slot): the settings cleared first if asked, a
/// window of `size` opened (openWindow; an invalid size keeps MainWindow's own) and `scene` (a
/// scene file or sample folder) opened in it unless empty. Null if the window system never
/// exposed it: `window_ = startWindow(); QVERIFY(window_ != nullptr);`.
inline std::unique_ptr<MainWindow> startWindow(QSize size = QSize(1000, 760), StartSettings settings = StartSettings::Kept,
                                               const std::filesystem::path& scene = {}) {
  if (settings == StartSettings::Cleared) QSettings().clear();
  auto window = openWindow(size);
  if (window && !scene.empty()) window->openScene(scene);
  return window;
}

/// The user's settings and data folders for a test run, in a temporary folder (XDG_CONFIG_HOME
/// and XDG_DATA_HOME, set before the QApplication reads them): a test never reads or changes the
/// user's window layout, recent files or recovery files. A process the test starts inherits them.
class TemporaryUserFolders {
 public:
  TemporaryUserFolders() {
    if (qEnvironmentVariableIsSet("FFDKIT_TEST_USER_FOLDERS")) return;  // started by a test: its folders
    qputenv("XDG_CONFIG_HOME", QFile::encodeName(dir_.filePath("config")));
    qputenv("XDG_DATA_HOME", QFile::encodeName(dir_.filePath("data")));
    qputenv("FFDKIT_TEST_USER_FOLDERS", QFile::encodeName(dir_.path()));
  }

 private:
  QTemporaryDir dir_;
};

/// Answers the modal dialogs that the next actions open, in order: each handler gets the
/// active modal widget (a QMessageBox, a QFileDialog, ...) and answers it, with real events
/// where it clicks. `answered()` says how many were.
class ModalAnswers : public QObject {
 public:
  using Handler = std::function<void(QWidget*)>;
  explicit ModalAnswers(std::vector<Handler> handlers) : handlers_(handlers.begin(), handlers.end()) {
    connect(&poll_, &QTimer::timeout, this, [this] {
      QWidget* modal = QApplication::activeModalWidget();
      if (modal == nullptr) return;
      if (modal->property("ffdkitAnswered").toBool()) {
        closeIfStuck(modal);
        return;
      }
      if (handlers_.empty()) return;
      modal->setProperty("ffdkitAnswered", true);
      Handler handler = std::move(handlers_.front());
      handlers_.pop_front();
      ++answered_;
      handler(modal);
    });
    poll_.start(20);
  }
  int answered() const { return answered_; }

 private:
  /// A dialog still open 10 s after its answer would block the test until CTest kills it: it
  /// fails the test, saying which dialog, and closes it.
  void closeIfStuck(QWidget* modal) {
    if (modal != stuck_) {
      stuck_ = modal;
      since_.start();
      return;
    }
    if (since_.elapsed() < 10000) return;
    const QString what = QString("%1 '%2' stayed open after its answer").arg(modal->metaObject()->className(), modal->windowTitle());
    QTest::qFail(qPrintable(what), __FILE__, __LINE__);
    modal->close();
    stuck_ = nullptr;
  }

  QTimer poll_;
  std::deque<Handler> handlers_;
  int answered_ = 0;
  QPointer<QWidget> stuck_;
  QElapsedTimer since_;
};

/// main() of a GUI test: VTK's surface format and temporary user folders before the
/// QApplication, then the Qt Test run.
template <class Test>
int runGuiTest(int argc, char** argv) {
  static TemporaryUserFolders folders;
  QSurfaceFormat::setDefaultFormat(VtkViewWidget::defaultFormat());
  QApplication app(argc, argv);
  Test test;
  return QTest::qExec(&test, argc, argv);
}

}  // namespace ffdkit::app::testing
