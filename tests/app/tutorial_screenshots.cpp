// The pictures of docs/tutorials/fig6-2-in-the-app.md, made by building the thesis's Fig. 6-2
// tool (Kuriyama 1996, secs. 6.4, 6.5) in the real window with real mouse and key events: the
// menus are opened and their items clicked on the menu bar, points are clicked in the 3D view,
// values are typed. Every step checks the document (lattices, selected points, cells,
// widgets, variations) before its picture is saved, and the finished tool must equal the
// scripted fixture (widgets::buildFig62) within 1e-12.
//
//   FFDKIT_TUTORIAL_IMAGES=docs/tutorials/images tutorial_screenshots   (scripts/tutorial-screenshots.sh)
//
// Without FFDKIT_TUTORIAL_IMAGES (CTest) the pictures go to a temporary folder and only their
// presence, size and that they are not blank are checked: pixels differ between machines.
#include <QDir>
#include <QImage>
#include <QLabel>
#include <QScreen>
#include <QStatusBar>

#include <numbers>
#include <set>

#include "ffdkit/widgets/thesis_examples.h"
#include "fig62_steps.h"
#include "gui_test_support.h"

using namespace ffdkit;
using app::MainWindow;
using widgets::WidgetId;
using namespace ffdkit::app::testing;

namespace {

// The window's size in the pictures (logical pixels).
const QSize kWindowSize(960, 680);

// The menu of the menu bar that holds `item`.
QMenu* menuOf(MainWindow& w, QAction* item) {
  for (QObject* owner : item->associatedObjects())
    if (auto* menu = qobject_cast<QMenu*>(owner); menu != nullptr && w.menuBar()->actions().contains(menu->menuAction()))
      return menu;
  return nullptr;
}

}  // namespace

class TutorialScreenshots : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    const QString folder = qEnvironmentVariable("FFDKIT_TUTORIAL_IMAGES");
    folder_ = folder.isEmpty() ? scratch_.path() : QDir(folder).absolutePath();
    QVERIFY(QDir().mkpath(folder_));
  }

  void fig62InTheApp() {
    auto window = openWindow(kWindowSize);
    QVERIFY(window != nullptr);
    MainWindow& w = *window;
    const auto& m = w.scene().widgets;
    QVERIFY(m.roots().empty());
    save(w, "01-empty-window");

    // Step 1: Widgets > New Lattice..., the dialog's defaults (3 x 3 x 3, Bernstein), OK.
    QAction* newLattice = action(w, "actionNewLattice");
    openMenu(w, newLattice);
    saveScreen(w, "02-widgets-menu");
    QDialog* seenDialog = nullptr;
    QTimer::singleShot(0, [&] {
      auto* dialog = qobject_cast<QDialog*>(QApplication::activeModalWidget());
      if (dialog == nullptr) return;
      seenDialog = dialog;
      QVERIFY(dialog->grab().save(folder_ + "/03-new-lattice-dialog.png"));
      saved_.push_back("03-new-lattice-dialog");
      dialog->accept();
    });
    clickMenuItem(w, newLattice);
    QVERIFY(seenDialog != nullptr);
    QCOMPARE(m.roots().size(), std::size_t(1));
    const WidgetId lattice = m.roots().front();
    QCOMPARE(m.counts(lattice), Eigen::Vector3i(3, 3, 3));
    lookAtUnitBox(w);
    save(w, "04-new-lattice");

    // Step 2: Tab: the lattice's edit mode; the four points of the top face's corner quad.
    pressKey(w, Qt::Key_Tab);
    QVERIFY(w.editController().editing());
    QVERIFY(selectPoints(w, lattice, fig62FacePoints()));
    QCOMPARE(w.editController().points().indices(), sorted(fig62FacePoints()));
    save(w, "05-face-points-selected");

    // Step 3: Ctrl+M makes them a face cell; Widgets > Add Rotate Widget puts a ring on it.
    const WidgetId ring = makeCellWithWidget(w, "actionAddRotate");
    QVERIFY(ring.valid());
    QCOMPARE(m.affineKind(ring), widgets::AffineKind::Rotate);
    QCOMPARE(m.cellIndices(*m.attachedCell(ring)).size(), std::size_t(4));
    save(w, "06-ring-on-the-face");

    // Step 4: the edge's two points, a cell, a translate widget; the same for the corner point.
    QVERIFY(selectPoints(w, lattice, fig62EdgePoints()));
    const WidgetId edgeArrow = makeCellWithWidget(w, "actionAddTranslate");
    QVERIFY(edgeArrow.valid());
    QCOMPARE(m.cellIndices(*m.attachedCell(edgeArrow)).size(), std::size_t(2));
    QVERIFY(selectPoints(w, lattice, fig62PointPoints()));
    const WidgetId pointArrow = makeCellWithWidget(w, "actionAddTranslate");
    QVERIFY(pointArrow.valid());
    QCOMPARE(m.cellIndices(*m.attachedCell(pointArrow)).size(), std::size_t(1));
    QCOMPARE(m.widgets(widgets::WidgetType::Affine).size(), std::size_t(3));
    save(w, "07-three-widgets");

    // Step 5: Tab leaves the edit mode; the corner's arrow turned to point up: its
    // transformer's y ring pressed, -90 typed, Return.
    pressKey(w, Qt::Key_Tab);
    QVERIFY(!w.editController().editing());
    turnWithTransformerRingY(w, pointArrow, "-90", [&] { save(w, "08-arrow-turned-by-typing"); });
    QVERIFY((m.affineFrame(pointArrow).frame.linear().col(0) - Eigen::Vector3d::UnitZ()).norm() < 1e-15);

    // Step 6: each widget dragged, the amount typed while the button is down.
    dragTyped(w, ring, "5", [&] { save(w, "09-ring-dragged"); });
    QVERIFY(std::abs(m.variation(ring) - 5.0 * std::numbers::pi / 180.0) < 1e-12);
    dragTyped(w, edgeArrow, "0.5");
    QVERIFY(std::abs(m.variation(edgeArrow) - 0.5) < 1e-12);
    dragTyped(w, pointArrow, "0.25");
    QVERIFY(std::abs(m.variation(pointArrow) - 0.25) < 1e-12);
    w.controller().clearSelection();
    save(w, "10-fig6-2-done");

    // The tool equals the scripted fixture.
    widgets::Fig62 fixture = widgets::buildFig62();
    fixture.model.applyVariation(fixture.faceRotate, 5.0 * std::numbers::pi / 180.0);
    fixture.model.applyVariation(fixture.edgeTranslate, 0.5);
    fixture.model.applyVariation(fixture.pointTranslate, 0.25);
    const double error = (m.worldControlPoints(lattice) - fixture.model.worldControlPoints(fixture.lattice)).cwiseAbs().maxCoeff();
    QVERIFY2(error <= 1e-12, qPrintable(QString("max |GUI - fixture| = %1").arg(error)));

    // Step 7: Ctrl+Z undoes the last drag (the document's state, not just the picture).
    const Eigen::MatrixX3d before = m.controlPoints(lattice);
    pressKey(w, Qt::Key_Z, Qt::ControlModifier);
    QVERIFY(std::abs(m.variation(pointArrow)) < 1e-12);
    QVERIFY((m.controlPoints(lattice) - before).cwiseAbs().maxCoeff() > 0.1);
    pressKey(w, Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);
    QVERIFY((m.controlPoints(lattice) - before).cwiseAbs().maxCoeff() < 1e-12);
  }

  void cleanupTestCase() {
    // Every picture exists, has a size, and is not blank (more than a handful of colours).
    QCOMPARE(saved_.size(), std::size_t(10));
    for (const QString& name : saved_) {
      const QImage image(folder_ + "/" + name + ".png");
      QVERIFY2(!image.isNull(), qPrintable(name));
      QVERIFY2(image.width() >= 200 && image.height() >= 100, qPrintable(name));
      std::set<QRgb> colours;
      for (int y = 0; y < image.height() && colours.size() <= 16; y += 7)
        for (int x = 0; x < image.width() && colours.size() <= 16; x += 7) colours.insert(image.pixel(x, y));
      QVERIFY2(colours.size() > 16, qPrintable(name + " is blank"));
    }
  }

 private:
  static std::vector<Eigen::Index> sorted(std::vector<Eigen::Index> v) {
    std::sort(v.begin(), v.end());
    return v;
  }

  // The window as it draws itself (the 3D view included).
  void save(MainWindow& w, const QString& name) {
    w.view()->grabFramebuffer();
    QVERIFY2(w.grab().save(folder_ + "/" + name + ".png"), qPrintable(name));
    saved_.push_back(name);
  }

  // The screen over the window, with the open menu (a window of its own).
  void saveScreen(MainWindow& w, const QString& name) {
    QApplication::processEvents();
    const QRect area = w.frameGeometry();
    const QPixmap shot = w.screen()->grabWindow(0, area.x(), area.y(), area.width(), area.height());
    QVERIFY2(shot.save(folder_ + "/" + name + ".png"), qPrintable(name));
    saved_.push_back(name);
  }

  // Clicks the menu bar's title of the menu that holds `item`: the menu opens.
  void openMenu(MainWindow& w, QAction* item) {
    QMenu* menu = menuOf(w, item);
    QVERIFY2(menu != nullptr, qPrintable(item->objectName()));
    QMenuBar* bar = w.menuBar();
    QTest::mouseClick(bar, Qt::LeftButton, Qt::NoModifier, bar->actionGeometry(menu->menuAction()).center());
    QTRY_VERIFY(menu->isVisible());
  }

  // Clicks `item` in its open menu.
  void clickMenuItem(MainWindow& w, QAction* item) {
    QMenu* menu = menuOf(w, item);
    QVERIFY(menu != nullptr && menu->isVisible());
    QTest::mouseClick(menu, Qt::LeftButton, Qt::NoModifier, menu->actionGeometry(item).center());
  }

  QTemporaryDir scratch_;
  QString folder_;
  std::vector<QString> saved_;
};

int main(int argc, char** argv) { return runGuiTest<TutorialScreenshots>(argc, argv); }

#include "tutorial_screenshots.moc"
