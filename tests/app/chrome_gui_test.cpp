// The details a new user meets first, under a real window and real events (Xvfb): no VTK
// default key reaches the view; Undo / Redo keep their width; status messages go when they stop
// being true; refusals name widgets and fit one line; the dock layout is remembered; the press's crank
// turns as it is dragged; a child lattice lists what it deforms.
#include <QAction>
#include <QDockWidget>
#include <QLabel>
#include <QMenu>
#include <QRegularExpression>
#include <QSettings>
#include <QStatusBar>
#include <QToolBar>
#include <QToolButton>
#include <QTreeWidget>
#include <QWindow>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <set>

#include <vtkActor.h>
#include <vtkActorCollection.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkProperty.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>

#include "ffdkit/interaction/interaction_controller.h"
#include "gui_test_support.h"

using namespace ffdkit;
using namespace ffdkit::app::testing;
using app::MainWindow;
using widgets::WidgetId;

namespace {

// Lets the layouts settle: the events a resize or a new message posts, and those they post.
void settleLayouts() {
  for (int round = 0; round < 3; ++round) QApplication::processEvents();
}

// Everything a VTK default key would change, read from the view.
struct ViewState {
  Eigen::Vector3d position, focal, up;
  int stereo = 0;
  std::vector<int> representations;
  std::size_t steps = 0;
  bool directManipulation = false;
  QImage image;

  static ViewState of(MainWindow& w) {
    settleLayouts();
    ViewState s;
    vtkCamera* camera = w.view()->renderer()->GetActiveCamera();
    camera->GetPosition(s.position.data());
    camera->GetFocalPoint(s.focal.data());
    camera->GetViewUp(s.up.data());
    s.stereo = w.view()->renderWindow()->GetStereoRender();
    vtkActorCollection* actors = w.view()->renderer()->GetActors();
    actors->InitTraversal();
    while (vtkActor* actor = actors->GetNextActor()) s.representations.push_back(actor->GetProperty()->GetRepresentation());
    s.steps = w.commands().position();
    s.directManipulation = action(w, "actionDirectManipulation")->isChecked();
    s.image = w.view()->grabFramebuffer();
    return s;
  }
};

}  // namespace

class ChromeGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    window_ = startWindow(QSize(1100, 760), StartSettings::Cleared);
    QVERIFY(window_ != nullptr);
  }
  void cleanup() { window_.reset(); }

  // Every letter and digit key pressed on the view: VTK's interactor sees none of them, and
  // nothing changes unless ffdkit binds the key (then it does what its action says).
  void noVtkDefaultKeyReachesTheView() {
    MainWindow& w = *window_;
    w.openScene(kExamples / "default");
    int vtkKeys = 0;
    vtkNew<vtkCallbackCommand> counter;
    counter->SetClientData(&vtkKeys);
    counter->SetCallback([](vtkObject*, unsigned long, void* count, void*) { ++*static_cast<int*>(count); });
    vtkRenderWindowInteractor* interactor = w.view()->interactor();
    for (unsigned long e : {vtkCommand::KeyPressEvent, vtkCommand::KeyReleaseEvent, vtkCommand::CharEvent})
      interactor->AddObserver(e, counter);
    // ffdkit's own single keys (action shortcuts without modifiers, keyboard_shortcuts.h).
    std::map<int, QAction*> bound;
    for (QAction* a : w.findChildren<QAction*>())
      for (const QKeySequence& sequence : a->shortcuts())
        if (sequence.count() == 1 && sequence[0].keyboardModifiers() == Qt::NoModifier) bound[sequence[0].key()] = a;
    QVERIFY(bound.count(Qt::Key_D));  // Direct Manipulation: a bound key still works below

    const ViewState reference = ViewState::of(w);
    std::vector<int> keys;
    for (int k = Qt::Key_A; k <= Qt::Key_Z; ++k) keys.push_back(k);
    for (int k = Qt::Key_0; k <= Qt::Key_9; ++k) keys.push_back(k);
    int tested = 0;
    for (int k : keys) {
      pressKey(w, static_cast<Qt::Key>(k));
      // With Shift too (VTK's style reads the character): unless the key is ffdkit's, whose
      // shortcut Qt also matches shifted.
      if (!bound.count(k)) pressKey(w, static_cast<Qt::Key>(k), Qt::ShiftModifier);
      QApplication::processEvents();
      const QString name = QKeySequence(k).toString();
      QVERIFY2(w.isVisible(), qPrintable(name + " closed the window"));
      QVERIFY2(vtkKeys == 0, qPrintable(name + " reached VTK's interactor"));
      if (bound.count(k)) {
        // ffdkit's key did what its action does (each is tested where it is built; D here):
        // a mode goes back off and the scene is opened again for the next key.
        QAction* a = bound[k];
        if (k == Qt::Key_D) QVERIFY(a->isChecked() != reference.directManipulation);
        if (a->isCheckable() && a->isChecked()) a->trigger();
        w.openScene(kExamples / "default");
        continue;
      }
      const ViewState now = ViewState::of(w);
      QVERIFY2(now.position == reference.position && now.focal == reference.focal && now.up == reference.up,
               qPrintable(name + " moved the camera"));
      QVERIFY2(now.stereo == reference.stereo, qPrintable(name + " changed stereo"));
      QVERIFY2(now.representations == reference.representations, qPrintable(name + " changed a representation"));
      QVERIFY2(now.steps == reference.steps, qPrintable(name + " edited the scene"));
      QVERIFY2(now.directManipulation == reference.directManipulation, qPrintable(name));
      QVERIFY2(now.image == reference.image, qPrintable(name + " changed the picture"));
      ++tested;
    }
    const auto boundHere = std::count_if(keys.begin(), keys.end(), [&](int k) { return bound.count(k) > 0; });
    QCOMPARE(tested, static_cast<int>(keys.size()) - static_cast<int>(boundHere));
    // The mouse still drives the view: a drag on empty space orbits the camera.
    dragPixels(w, QPoint(40, 40), QPoint(140, 60));
    QVERIFY(ViewState::of(w).position != reference.position);
  }

  // The toolbar's Undo / Redo keep their width whatever the step; the step is named in the
  // tooltip and in the Edit menu.
  void undoAndRedoKeepTheirWidthAndNameTheStepElsewhere() {
    MainWindow& w = *window_;
    w.openScene(kExamples / "default");
    auto* toolbar = w.findChild<QToolBar*>("operationsToolbar");
    QVERIFY(toolbar != nullptr);
    QWidget* undoButton = toolbar->widgetForAction(action(w, "actionUndo"));
    QWidget* redoButton = toolbar->widgetForAction(action(w, "actionRedo"));
    QApplication::processEvents();
    const int undoWidth = undoButton->width(), redoWidth = redoButton->width();
    const QPoint undoAt = undoButton->pos();
    // A step with a long name: drag the arrow on the sphere.
    const widgets::WidgetFrame f = w.scene().widgets.affineFrame(w.scene().widgets.find("pull"));
    const Eigen::Vector3d x = f.frame.linear().col(0), grab = f.frame.translation() + 0.6 * f.size * x;
    dragWorld(w, grab, grab + 0.2 * x);
    QApplication::processEvents();
    QVERIFY(w.commands().canUndo());
    const QString step = QString::fromStdString(w.commands().undoDescription());
    QVERIFY(step.contains("pull"));
    QCOMPARE(undoButton->width(), undoWidth);
    QCOMPARE(undoButton->pos(), undoAt);
    QVERIFY(undoButton->toolTip().contains(step));
    QVERIFY(action(w, "actionUndo")->text().contains(step));
    QCOMPARE(qobject_cast<QToolButton*>(undoButton)->text(), QObject::tr("Undo"));
    // Undone with the toolbar button: now Redo names it, and keeps its width too.
    QTest::mouseClick(undoButton, Qt::LeftButton);
    QApplication::processEvents();
    QVERIFY(action(w, "actionRedo")->text().contains(step));
    QVERIFY(redoButton->toolTip().contains(step));
    QCOMPARE(redoButton->width(), redoWidth);
    QCOMPARE(undoButton->width(), undoWidth);
  }

  // A message goes when it stops being true: a refusal when the next edit succeeds, the
  // transformer's running value when its drag ends.
  void statusMessagesClearWhenTheyStopBeingTrue() {
    MainWindow& w = *window_;
    w.openScene(kExamples / "default");
    QVERIFY(w.statusMessage().contains("1 objects"));
    action(w, "actionBind")->trigger();  // nothing selected: refused
    QVERIFY2(w.statusMessage().contains("select exactly two widgets"), qPrintable(w.statusMessage()));
    const widgets::WidgetFrame f = w.scene().widgets.affineFrame(w.scene().widgets.find("pull"));
    const Eigen::Vector3d x = f.frame.linear().col(0), grab = f.frame.translation() + 0.6 * f.size * x;
    dragWorld(w, grab, grab + 0.2 * x);  // an edit: the refusal is no longer true
    QCOMPARE(w.statusMessage(), QString());
    // The transformer of the selected arrow: "move ..." while dragging, gone after.
    QVERIFY(w.controller().transformer().has_value());
    const app::Transformer t = *w.controller().transformer();
    const Eigen::Vector3d z = t.frame.linear().col(2), o = t.frame.translation();
    const Eigen::Vector3d shaft = o + 0.6 * t.size * z;
    const QPoint a = toWidget(w, shaft), b = toWidget(w, shaft + 0.2 * z);
    sendMouse(w.view(), QEvent::MouseButtonPress, a, Qt::LeftButton, Qt::LeftButton);
    for (int step = 1; step <= 10; ++step)
      sendMouse(w.view(), QEvent::MouseMove, a + (b - a) * step / 10, Qt::NoButton, Qt::LeftButton);
    QVERIFY2(w.statusMessage().startsWith("move z"), qPrintable(w.statusMessage()));
    sendMouse(w.view(), QEvent::MouseButtonRelease, b, Qt::LeftButton, Qt::NoButton);
    QCOMPARE(w.statusMessage(), QString());
  }

  // Binding two widgets that are already bound is refused; the message names them (no "w7",
  // no "b0"). In a narrow window it is cut to one line with an ellipsis, read whole in the
  // line's tooltip, and neither the status bar nor the 3D view changes height for it.
  void aRefusalNamesWidgetsByNameOnOneLine() {
    MainWindow& w = *window_;
    w.resize(640, 700);
    w.openScene(kExamples / "mirror");
    clickRow(w, "push-front");
    clickRow(w, "push-back", Qt::ControlModifier);
    QCOMPARE(w.controller().selection().size(), std::size_t(2));
    settleLayouts();
    const QSize view = w.view()->size();
    auto* line = w.findChild<QLabel*>("statusMessage");
    QVERIFY(line != nullptr);
    const int lineHeight = line->height();
    action(w, "actionBind")->trigger();
    const QString message = w.statusMessage();
    QVERIFY2(message.contains("'push-front'") && message.contains("'push-back'") && message.contains("already bound"),
             qPrintable(message));
    QVERIFY2(!QRegularExpression(R"(\b[wb][0-9]+\b)").match(message).hasMatch(), qPrintable(message));
    settleLayouts();
    QVERIFY2(line->fontMetrics().horizontalAdvance(message) > line->contentsRect().width(),
             "the message should not fit on the line here");
    QCOMPARE(line->toolTip(), message);
    QVERIFY2(line->text().endsWith(QChar(0x2026)) && message.startsWith(line->text().chopped(1)), qPrintable(line->text()));
    QVERIFY2(line->fontMetrics().horizontalAdvance(line->text()) <= line->contentsRect().width(), qPrintable(line->text()));
    QCOMPARE(line->height(), lineHeight);
    QCOMPARE(w.view()->size(), view);
  }

  // The 3D view changes size only when the user resizes something: messages in the status line
  // (a long refusal, a count, none) and the panels showing other things (an object, a lattice,
  // an arrow, two widgets) leave the view, the status bar and the docks as they were.
  void theViewKeepsItsSizeWhileMessagesAndPanelsChange() {
    MainWindow& w = *window_;
    w.resize(640, 480);
    w.openScene(kExamples / "mirror");
    settleLayouts();
    auto* outliner = w.findChild<QDockWidget*>("outlinerDock");
    auto* properties = w.findChild<QDockWidget*>("propertiesDock");
    QVERIFY(outliner != nullptr && properties != nullptr && outliner->isVisible() && properties->isVisible());
    const QSize view = w.view()->size(), bar = w.statusBar()->size();
    const int outlinerWidth = outliner->width(), propertiesWidth = properties->width();
    QStringList said;
    // What changed size after `step`, or nothing.
    auto changed = [&](const char* step) -> QString {
      settleLayouts();
      said << w.statusMessage();
      const QString where = QString("after %1 (status '%2')").arg(step, w.statusMessage());
      if (w.view()->size() != view)
        return where + QString(": view %1 x %2, was %3 x %4").arg(w.view()->width()).arg(w.view()->height()).arg(view.width()).arg(view.height());
      if (w.statusBar()->size() != bar) return where + ": the status bar";
      if (outliner->width() != outlinerWidth || properties->width() != propertiesWidth)
        return where + QString(": docks %1 and %2 wide, were %3 and %4")
                           .arg(outliner->width()).arg(properties->width()).arg(outlinerWidth).arg(propertiesWidth);
      return {};
    };
#define FFDKIT_UNCHANGED(step)                 \
  do {                                         \
    const QString problem = changed(step);     \
    QVERIFY2(problem.isEmpty(), qPrintable(problem)); \
  } while (false)
    clickRow(w, "torus");
    FFDKIT_UNCHANGED("selecting the object");
    clickRow(w, "lattice");
    FFDKIT_UNCHANGED("selecting the lattice");
    clickRow(w, "push-front");
    FFDKIT_UNCHANGED("selecting an arrow");
    clickRow(w, "push-back", Qt::ControlModifier);
    FFDKIT_UNCHANGED("selecting two arrows");
    clickMenuItem(w, action(w, "actionBind"));
    FFDKIT_UNCHANGED("a refused binding");
    pressKey(w, Qt::Key_Escape);
    FFDKIT_UNCHANGED("Esc");
    clickRow(w, "face-front");
    FFDKIT_UNCHANGED("selecting a cell");
#undef FFDKIT_UNCHANGED
    // The refusal was said (on one line, too long for it), and then cleared.
    QVERIFY2(std::any_of(said.begin(), said.end(), [](const QString& m) { return m.contains("already bound"); }),
             qPrintable(said.join(" | ")));
    QVERIFY2(said.contains(QString()), qPrintable(said.join(" | ")));
  }

  // Docks are resized with the mouse; the layout and the window size come back next time.
  void theDockLayoutIsRememberedAcrossSessions() {
    MainWindow& w = *window_;
    auto* properties = w.findChild<QDockWidget*>("propertiesDock");
    QVERIFY(properties != nullptr);
    QApplication::processEvents();
    const int before = properties->width();
    QVERIFY2(before >= 300, qPrintable(QString::number(before)));  // not narrow
    // The separator between the view and the properties dock: drag it 120 px to the left.
    const QPoint grip((w.centralWidget()->geometry().right() + properties->geometry().left()) / 2,
                      properties->geometry().center().y());
    sendMouse(&w, QEvent::MouseButtonPress, grip, Qt::LeftButton, Qt::LeftButton);
    for (int dx = 10; dx <= 120; dx += 10) {
      sendMouse(&w, QEvent::MouseMove, grip - QPoint(dx, 0), Qt::NoButton, Qt::LeftButton);
      QApplication::processEvents();  // the layout moves the separator on a timer
    }
    sendMouse(&w, QEvent::MouseButtonRelease, grip - QPoint(120, 0), Qt::LeftButton, Qt::NoButton);
    QApplication::processEvents();
    const int widened = properties->width();
    QVERIFY2(std::abs(widened - (before + 120)) <= 6, qPrintable(QString("%1 -> %2").arg(before).arg(widened)));
    w.resize(1000, 700);
    QApplication::processEvents();
    QVERIFY(w.close());
    window_.reset();

    window_ = openWindow();
    QVERIFY(window_ != nullptr);
    QApplication::processEvents();
    QCOMPARE(window_->size(), QSize(1000, 700));
    const int restored = window_->findChild<QDockWidget*>("propertiesDock")->width();
    QVERIFY2(std::abs(restored - widened) <= 6, qPrintable(QString("%1 vs %2").arg(restored).arg(widened)));
  }

  // press: the handle is the crank; dragging its knob turns it (the knob follows the pointer)
  // and the screw lowers the top face.
  void thePressCrankTurnsAsItIsDragged() {
    MainWindow& w = *window_;
    w.openScene(kExamples / "press");
    const auto& m = w.scene().widgets;
    const WidgetId handle = m.find("handle"), press = m.find("press");
    const widgets::WidgetFrame f = m.affineFrame(handle);
    const Eigen::Vector3d o = f.frame.translation(), x = f.frame.linear().col(0), y = f.frame.linear().col(1);
    const double start = m.variation(handle), pressStart = m.variation(press);
    auto onCircle = [&](double angle, double radius) {
      return Eigen::Vector3d(o + radius * f.size * (std::cos(angle) * x + std::sin(angle) * y));
    };
    auto isCrank = [&](const QImage& image, const Eigen::Vector3d& p) {
      int green = 0;
      const QPoint c = toWidget(w, p) * w.view()->devicePixelRatioF();
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy) {
          const QColor colour = image.pixelColor(c + QPoint(dx, dy));
          green += colour.green() > colour.red() + 40 && colour.green() > colour.blue() + 40;
        }
      return green >= 5;
    };
    QVERIFY2(isCrank(w.view()->grabFramebuffer(), onCircle(start, 0.6)), "the crank's arm lies at its variation");
    const double turn = std::numbers::pi / 3;
    dragWorld(w, onCircle(start, 1.0), onCircle(start + turn, 1.0));
    QVERIFY2(std::abs(m.variation(handle) - start - turn) < 0.05, qPrintable(QString::number(m.variation(handle) - start)));
    QVERIFY(std::abs(m.variation(press) - pressStart - 0.4 * (m.variation(handle) - start) / (2 * std::numbers::pi)) < 1e-9);
    // Dismiss the selection (and its transformer), then look: the arm has turned with the drag.
    click(w, QPoint(5, 5));
    const QImage image = w.view()->grabFramebuffer();
    QVERIFY2(isCrank(image, onCircle(start + turn, 0.6)), "the arm follows the pointer");
    QVERIFY2(!isCrank(image, onCircle(start, 0.6)), "the arm left its old place");
  }

  // hierarchy: the child lattice's panel lists the column, which it deforms through its root.
  void aChildLatticeListsWhatItDeformsThroughItsRoot() {
    MainWindow& w = *window_;
    w.openScene(kExamples / "hierarchy");
    clickRow(w, "child");
    QApplication::processEvents();
    QLabel* deforms = nullptr;
    for (QLabel* label : w.findChildren<QLabel*>("deforms"))
      if (label->isVisible()) deforms = label;
    QVERIFY(deforms != nullptr);
    QCOMPARE(deforms->text(), QString("column (through parent)"));
  }

 private:
  std::unique_ptr<MainWindow> window_;
};

int main(int argc, char** argv) { return runGuiTest<ChromeGuiTest>(argc, argv); }

#include "chrome_gui_test.moc"
