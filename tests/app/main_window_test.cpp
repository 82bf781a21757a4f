// The application under a real window and real Qt events (Xvfb): the thesis operations through
// actions, dialogs, the outliner and the property panel; glyph drags with the mouse; undo;
// widget files; the sample scenes on screen.
#include <QAction>
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QApplication>
#include <QDialog>
#include <QFileDialog>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QMouseEvent>
#include <QSettings>
#include <QSpinBox>
#include <QStatusBar>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QTest>
#include <QTimer>
#include <QToolButton>
#include <QTreeWidget>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include <vtkCamera.h>
#include <vtkRenderer.h>

#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/gui/main_window.h"
#include "ffdkit/render/scene_view.h"
#include "ffdkit/viewhost/vtk_view_widget.h"
#include "ffdkit/scenes/mesh_io.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/widget_file.h"
#include "gui_test_support.h"
#include "lifecycle_dialog_answers.h"

using namespace ffdkit;
using namespace ffdkit::app::testing;
using app::MainWindow;
using widgets::WidgetId;

namespace {

// Triggers an action that opens a modal dialog; `fill` sets its fields (or answers it), then it is
// accepted if still open.
void triggerWithDialog(MainWindow& w, const char* name, std::function<void(QDialog*)> fill = {}) {
  bool seen = false;
  QTimer::singleShot(0, [&] {
    auto* dialog = qobject_cast<QDialog*>(QApplication::activeModalWidget());
    if (dialog == nullptr) return;
    seen = true;
    if (fill) fill(dialog);
    if (dialog->isVisible()) dialog->accept();
  });
  action(w, name)->trigger();
  QVERIFY2(seen, name);
}

// Triggers a File action whose file dialog is answered with `path`.
void triggerWithFile(MainWindow& w, const char* name, const QString& path) {
  triggerWithDialog(w, name, [&](QDialog* dialog) {
    auto* files = qobject_cast<QFileDialog*>(dialog);
    QVERIFY(files != nullptr);
    const QString failure = chooseFilePath(files, path.toStdString());
    QVERIFY2(failure.isEmpty(), qPrintable(failure));
  });
}

double maxDifference(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) { return (a - b).cwiseAbs().maxCoeff(); }

// The property panel's control named `name` now on screen. The panel rebuilds itself after every
// edit: the new rows are shown and the previous ones deleted by posted events, delivered here.
template <class T>
T* panelControl(MainWindow& w, const char* name) {
  QApplication::processEvents();
  QApplication::sendPostedEvents(nullptr, QEvent::DeferredDelete);
  for (T* control : w.findChildren<T*>(name))
    if (control->isVisible()) return control;
  return nullptr;
}

// Drags a rotate widget's ring by `angle` radians about its axis (in the ring's plane).
void dragRing(MainWindow& w, WidgetId affine, double angle) {
  const widgets::WidgetFrame f = w.scene().widgets.affineFrame(affine);
  const Eigen::Vector3d o = f.frame.translation(), x = f.frame.linear().col(0), y = f.frame.linear().col(1);
  dragWorld(w, o + f.size * x, o + f.size * (std::cos(angle) * x + std::sin(angle) * y));
}

Eigen::Index flat(int i, int j, int k) { return i + 3 * (j + 3 * k); }

// Through the UI: a sphere, a 3x3x3 lattice, a translate widget on each of the given lattice
// points (picked with the mouse), the lattice attached to the sphere. Returns the widgets.
std::vector<WidgetId> buildSphereWithWidgets(MainWindow& w, const std::vector<Eigen::Index>& points) {
  std::vector<WidgetId> out;
  triggerWithDialog(w, "actionAddPrimitive");
  if (w.scene().objects().size() != 1) return out;
  triggerWithDialog(w, "actionNewLattice");
  const auto roots = w.scene().widgets.roots();
  if (roots.size() != 1) return out;
  for (Eigen::Index index : points) {
    const Eigen::Vector3d p = w.scene().widgets.worldControlPoints(roots.front()).row(index);
    click(w, toWidget(w, p));
    const auto picked = w.controller().pickedPoint();
    if (!picked || picked->index != index) return {};
    action(w, "actionAddTranslate")->trigger();
    out.push_back(w.scene().widgets.widgets(widgets::WidgetType::Affine).back());
  }
  action(w, "actionAttach")->trigger();
  return out;
}

// buildSphereWithWidgets with translate widgets on the top and bottom centre points, both then
// selected in the outliner (click, Ctrl+click), ready for Bind Two Widgets.
std::vector<WidgetId> selectTwoWidgetsOnTheSphere(MainWindow& w) {
  const auto created = buildSphereWithWidgets(w, {flat(1, 1, 2), flat(1, 1, 0)});
  if (created.size() != 2) return created;
  clickRow(w, QString::fromStdString(w.scene().widgets.name(created[0])));
  clickRow(w, QString::fromStdString(w.scene().widgets.name(created[1])), Qt::ControlModifier);
  return created;
}

}  // namespace

class MainWindowTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    window_ = std::make_unique<MainWindow>();
    window_->show();
    QVERIFY(QTest::qWaitForWindowExposed(window_.get()));
    window_->view()->grabFramebuffer();  // a first frame sizes VTK's window
  }
  void cleanup() { window_.reset(); }

  void draggingAGlyphDeformsTheSphereAsTheModelPredictsAndUndoRestores() {
    MainWindow& w = *window_;
    const auto created = buildSphereWithWidgets(w, {flat(1, 1, 2)});
    QCOMPARE(created.size(), std::size_t(1));
    const WidgetId arrow = created.front();
    const std::string sphere = w.scene().objects().front().name;
    QCOMPARE(w.scene().latticesDeforming(sphere).size(), std::size_t(1));

    // Hovering over the arrow highlights it.
    const widgets::WidgetFrame frame = w.scene().widgets.affineFrame(arrow);
    const Eigen::Vector3d onArrow = frame.frame.translation() + 0.6 * frame.size * frame.frame.linear().col(0);
    sendMouse(w.view(), QEvent::MouseMove, toWidget(w, onArrow), Qt::NoButton, Qt::NoButton);
    QVERIFY(w.controller().hovered() == std::optional<WidgetId>(arrow));
    QVERIFY(w.sceneView().camera().position.norm() > 0.0);

    const Eigen::MatrixX3d before = w.deformer().points(sphere);
    scenes::Scene expected = w.scene();
    double camera[3];
    w.view()->renderer()->GetActiveCamera()->GetPosition(camera);

    dragArrow(w, arrow, 0.3);
    const double v = w.scene().widgets.variation(arrow);
    QVERIFY2(std::abs(v - 0.3) < 0.02, qPrintable(QString("variation %1").arg(v)));
    QVERIFY(maxDifference(w.deformer().points(sphere), before) > 0.05);
    double cameraAfter[3];
    w.view()->renderer()->GetActiveCamera()->GetPosition(cameraAfter);
    QCOMPARE(cameraAfter[0], camera[0]);  // a drag on a glyph does not orbit

    // The model with the same variation applied gives the same points.
    expected.widgets.setVariation(arrow, v);
    scenes::SceneDeformer model;
    model.update(expected);
    model.finishGesture(expected);
    QVERIFY(maxDifference(w.deformer().points(sphere), model.points(sphere)) < 1e-9);

    QVERIFY(action(w, "actionUndo")->isEnabled());
    action(w, "actionUndo")->trigger();
    QVERIFY(maxDifference(w.deformer().points(sphere), before) < 1e-12);
    QCOMPARE(w.scene().widgets.variation(arrow), 0.0);
  }

  void boundWidgetsMoveTogether() {
    MainWindow& w = *window_;
    const auto created = selectTwoWidgetsOnTheSphere(w);
    QCOMPARE(created.size(), std::size_t(2));
    const auto& m = w.scene().widgets;
    QCOMPARE(w.controller().selection().size(), std::size_t(2));
    const std::size_t bindings = m.bindings().size();
    action(w, "actionBind")->trigger();
    QCOMPARE(m.bindings().size(), bindings + 1);
    QCOMPARE(m.binding(m.bindings().back()).kind, widgets::BindingKind::Variation);

    const WidgetId otherCell = *m.attachedCell(created[1]);
    const Eigen::MatrixX3d otherBefore = m.cellWorldPoints(otherCell);
    dragArrow(w, created[0], 0.2);
    const double v0 = m.variation(created[0]), v1 = m.variation(created[1]);
    QVERIFY2(std::abs(v0 - 0.2) < 0.02, qPrintable(QString("variation %1").arg(v0)));
    QVERIFY(std::abs(v1 - v0) < 1e-12);
    QVERIFY(maxDifference(m.cellWorldPoints(otherCell), otherBefore) > 0.15);

    // The conversion rule in the property panel: gain 2, then a clamp of the driven widget.
    const widgets::BindingId variation = m.bindings().back();
    clickRow(w, QString::fromStdString(m.name(created[0]) + " <-> " + m.name(created[1])));
    auto* gain = w.findChild<QDoubleSpinBox*>("gain");
    QVERIFY(gain != nullptr);
    gain->setValue(2.0);
    QCOMPARE(m.binding(variation).rule.gain, 2.0);
    const double start1 = m.variation(created[1]);
    dragArrow(w, created[0], 0.1);
    QVERIFY(std::abs((m.variation(created[1]) - start1) - 2.0 * 0.1) < 0.03);
    auto* clampMax = w.findChild<QDoubleSpinBox*>("clampMax");
    auto* clamp = w.findChild<QCheckBox*>("clamp");
    QVERIFY(clampMax != nullptr && clamp != nullptr);
    clampMax->setValue(0.5);
    clamp->setChecked(true);
    QVERIFY(m.binding(variation).rule.clamp.has_value());
    dragArrow(w, created[0], 0.3);
    QVERIFY(m.variation(created[1]) <= 0.5 + 1e-9);
  }

  void editingACellMotionMaskChangesWhatFollows() {
    MainWindow& w = *window_;
    const auto created = buildSphereWithWidgets(w, {flat(1, 1, 2)});
    QCOMPARE(created.size(), std::size_t(1));
    const auto& m = w.scene().widgets;
    const WidgetId cellA = *m.attachedCell(created[0]);
    // A second point cell, made by adding a translate widget on the bottom-centre point.
    const WidgetId lattice = m.latticeOf(cellA);
    click(w, toWidget(w, m.worldControlPoints(lattice).row(flat(1, 1, 0))));
    action(w, "actionAddTranslate")->trigger();
    const WidgetId cellB = *m.attachedCell(m.widgets(widgets::WidgetType::Affine).back());
    clickRow(w, QString::fromStdString(m.name(cellA)));
    clickRow(w, QString::fromStdString(m.name(cellB)), Qt::ControlModifier);
    action(w, "actionBind")->trigger();
    const widgets::BindingId motion = m.bindings().back();
    QCOMPARE(m.binding(motion).kind, widgets::BindingKind::CellMotion);

    const Eigen::MatrixX3d bBefore = m.cellWorldPoints(cellB);
    dragArrow(w, created[0], 0.2);
    QVERIFY2(maxDifference(m.cellWorldPoints(cellB), bBefore) > 0.15, "cell B follows with mask TR");
    action(w, "actionUndo")->trigger();
    QVERIFY(maxDifference(m.cellWorldPoints(cellB), bBefore) < 1e-12);

    // Select the binding in the outliner and switch translation off with its T button.
    clickRow(w, QString::fromStdString(m.name(m.binding(motion).from) + " <-> " + m.name(m.binding(motion).to)));
    auto* maskT = w.findChild<QToolButton*>("maskT");
    QVERIFY(maskT != nullptr && maskT->isChecked());
    QTest::mouseClick(maskT, Qt::LeftButton);
    QVERIFY(!m.binding(motion).mask.translate);
    QVERIFY(m.binding(motion).mask.rotate);

    const Eigen::MatrixX3d aBefore = m.cellWorldPoints(cellA);
    dragArrow(w, created[0], 0.2);
    QVERIFY(maxDifference(m.cellWorldPoints(cellA), aBefore) > 0.15);
    QVERIFY2(maxDifference(m.cellWorldPoints(cellB), bBefore) < 1e-9, "translation no longer carried to cell B");
  }

  void theKindOfAWidgetIsChangedInThePropertyPanelAndItsDragThenRotates() {
    MainWindow& w = *window_;
    const auto created = buildSphereWithWidgets(w, {flat(1, 1, 2)});
    QCOMPARE(created.size(), std::size_t(1));
    const WidgetId widget = created.front();
    const auto& m = w.scene().widgets;
    clickRow(w, QString::fromStdString(m.name(widget)));
    auto* kind = panelControl<QComboBox>(w, "kind");
    QVERIFY(kind != nullptr);
    QCOMPARE(kind->currentText(), QString("translate"));
    kind->setCurrentIndex(kind->findText("rotate"));
    QCOMPARE(m.affineKind(widget), widgets::AffineKind::Rotate);
    QCOMPARE(m.glyph(widget).shape, std::string("ring"));
    QCOMPARE(panelControl<QComboBox>(w, "kind")->currentText(), QString("rotate"));
    // Tip the ring towards the camera (about x by 60 degrees) and put its axis beside the point, so
    // that turning it swings the point around the axis.
    panelControl<QDoubleSpinBox>(w, "orientationx")->setValue(60.0);
    panelControl<QDoubleSpinBox>(w, "placementy")->setValue(0.3);
    const WidgetId lattice = m.latticeOf(widget);
    const Eigen::Vector3d point0 = m.worldControlPoints(lattice).row(flat(1, 1, 2));
    const widgets::WidgetFrame frame = m.affineFrame(widget);
    const Eigen::Vector3d centre = frame.frame.translation(), axis = frame.frame.linear().col(2);

    dragRing(w, widget, 0.6);
    const double turned = m.variation(widget);
    QVERIFY2(std::abs(turned - 0.6) < 0.05, qPrintable(QString("variation %1 rad").arg(turned)));
    // The point turned about the ring's axis by the widget's variation.
    const Eigen::Vector3d point1 = m.worldControlPoints(lattice).row(flat(1, 1, 2));
    const Eigen::Vector3d expected = centre + Eigen::AngleAxisd(turned, axis) * (point0 - centre);
    QVERIFY2((point1 - expected).norm() < 1e-9, qPrintable(QString("off by %1").arg((point1 - expected).norm())));
    QVERIFY((point1 - point0).norm() > 0.05);
    // Undo the drag, then the kind.
    for (int i = 0; i < 4; ++i) action(w, "actionUndo")->trigger();
    QCOMPARE(m.affineKind(widget), widgets::AffineKind::Translate);
  }

  void aOneWayBindingOnlyCarriesMotionFromItsFromEnd() {
    MainWindow& w = *window_;
    const auto created = selectTwoWidgetsOnTheSphere(w);
    QCOMPARE(created.size(), std::size_t(2));
    const auto& m = w.scene().widgets;
    action(w, "actionBind")->trigger();
    const widgets::BindingId binding = m.bindings().back();
    QCOMPARE(m.binding(binding).kind, widgets::BindingKind::Variation);
    const WidgetId from = m.binding(binding).from, to = m.binding(binding).to;
    clickRow(w, QString::fromStdString(m.name(from) + " <-> " + m.name(to)));
    auto* oneWay = panelControl<QCheckBox>(w, "oneWay");
    QVERIFY(oneWay != nullptr && !oneWay->isChecked());
    QTest::mouseClick(oneWay, Qt::LeftButton);
    QVERIFY(m.binding(binding).oneWay);
    QVERIFY(panelControl<QCheckBox>(w, "oneWay")->isChecked());

    // Dragging `to` moves it alone.
    const double from0 = m.variation(from), to0 = m.variation(to);
    dragArrow(w, to, 0.2);
    QVERIFY2(std::abs(m.variation(to) - to0 - 0.2) < 0.02, qPrintable(QString("to moved %1").arg(m.variation(to) - to0)));
    QCOMPARE(m.variation(from), from0);
    // Dragging `from` still drives `to`.
    const double to1 = m.variation(to);
    dragArrow(w, from, 0.2);
    const double moved = m.variation(from) - from0;
    QVERIFY2(std::abs(moved - 0.2) < 0.02, qPrintable(QString("from moved %1").arg(moved)));
    QVERIFY(std::abs((m.variation(to) - to1) - moved) < 1e-12);
    // Undo the drags and the toggle: two-way again.
    for (int i = 0; i < 3; ++i) action(w, "actionUndo")->trigger();
    QVERIFY(!m.binding(binding).oneWay);
  }

  void latticeCountsAreRaisedInThePropertyPanelKeepingTheDeformationAndUndone() {
    MainWindow& w = *window_;
    const auto created = buildSphereWithWidgets(w, {flat(1, 1, 2)});
    QCOMPARE(created.size(), std::size_t(1));
    const auto& m = w.scene().widgets;
    const std::string sphere = w.scene().objects().front().name;
    const WidgetId lattice = m.latticeOf(created.front());
    dragArrow(w, created.front(), 0.3);
    const Eigen::MatrixX3d rest = w.scene().objects().front().mesh.points;
    const Eigen::MatrixX3d deformed = w.deformer().points(sphere);
    QVERIFY(maxDifference(deformed, rest) > 0.05);
    const Eigen::MatrixX3d control = m.controlPoints(lattice);

    clickRow(w, QString::fromStdString(m.name(lattice)));
    for (const char* name : {"countU", "countV", "countW"}) {
      auto* count = panelControl<QSpinBox>(w, name);
      QVERIFY2(count != nullptr, name);
      QCOMPARE(count->value(), 3);
      count->setValue(4);
      QCOMPARE(panelControl<QSpinBox>(w, name)->value(), 4);
    }
    QCOMPARE(m.counts(lattice), Eigen::Vector3i(4, 4, 4));
    QCOMPARE(m.cellSpec(*m.attachedCell(created.front())), widgets::CellSpec::point(2, 2, 3));
    // The dialog's default basis is Bernstein: 3 points per axis hold a tri-quadratic map, 4 a
    // tri-cubic one, so each raise is a degree elevation and the sphere keeps its shape up to
    // rounding in the embedding and evaluation (1e-9).
    const double change = maxDifference(w.deformer().points(sphere), deformed);
    qInfo("sphere points after 3x3x3 -> 4x4x4: moved by at most %.3g", change);
    QVERIFY2(change < 1e-9, qPrintable(QString("sphere moved by %1").arg(change)));

    for (int i = 0; i < 3; ++i) action(w, "actionUndo")->trigger();
    QCOMPARE(m.counts(lattice), Eigen::Vector3i(3, 3, 3));
    QCOMPARE(m.controlPoints(lattice), control);
    QVERIFY(maxDifference(w.deformer().points(sphere), deformed) < 1e-12);
  }

  void anEditTheModelRejectsIsReportedAndTheControlShowsTheModelAgain() {
    MainWindow& w = *window_;
    const auto created = buildSphereWithWidgets(w, {flat(1, 1, 2)});
    QCOMPARE(created.size(), std::size_t(1));
    const auto& m = w.scene().widgets;
    const WidgetId lattice = m.latticeOf(created.front());
    clickRow(w, QString::fromStdString(m.name(lattice)));
    const widgets::WidgetModelData before = m.toData();
    const QString undoText = action(w, "actionUndo")->text();

    // A cubic B-spline along u needs 4 points; the lattice has 3.
    auto* basisU = panelControl<QComboBox>(w, "basisU");
    QVERIFY(basisU != nullptr);
    QCOMPARE(basisU->currentText(), QString("Bernstein"));
    basisU->setCurrentIndex(basisU->findText("B-spline deg 3"));
    QVERIFY2(w.statusMessage().contains("degree"), qPrintable(w.statusMessage()));
    QCOMPARE(panelControl<QComboBox>(w, "basisU")->currentText(), QString("Bernstein"));
    QCOMPARE(m.latticeSettings(lattice).basis[0].kind, ffd::AxisBasis::Kind::Bernstein);
    QCOMPARE(action(w, "actionUndo")->text(), undoText);

    // A quadratic one fits; then 2 points along u no longer carry it.
    panelControl<QComboBox>(w, "basisU")->setCurrentIndex(panelControl<QComboBox>(w, "basisU")->findText("B-spline deg 2"));
    QCOMPARE(m.latticeSettings(lattice).basis[0].kind, ffd::AxisBasis::Kind::BSpline);
    const Eigen::MatrixX3d control = m.controlPoints(lattice);
    QCOMPARE(w.statusMessage(), QString());  // the refusal went with the next edit
    panelControl<QSpinBox>(w, "countU")->setValue(2);
    QVERIFY2(w.statusMessage().contains("along u"), qPrintable(w.statusMessage()));
    QCOMPARE(panelControl<QSpinBox>(w, "countU")->value(), 3);
    QCOMPARE(m.counts(lattice), Eigen::Vector3i(3, 3, 3));
    QCOMPARE(m.controlPoints(lattice), control);
    action(w, "actionUndo")->trigger();
    QCOMPARE(m.latticeSettings(lattice).basis[0].kind, ffd::AxisBasis::Kind::Bernstein);
    QCOMPARE(m.toData().lattices.front().controlPoints, before.lattices.front().controlPoints);
  }

  void aLargeObjectIsEmbeddedBehindAProgressDialog() {
    MainWindow& w = *window_;
    const long saved = MainWindow::backgroundEmbedPoints();
    MainWindow::setBackgroundEmbedPoints(100);  // the test sphere counts as large
    triggerWithDialog(w, "actionAddPrimitive");
    triggerWithDialog(w, "actionNewLattice");
    const std::string sphere = w.scene().objects().front().name;
    const WidgetId lattice = w.scene().widgets.roots().front();
    w.controller().addAffineAtPoint({lattice, flat(1, 1, 2)}, widgets::AffineKind::Translate);
    w.controller().setVariation(w.scene().widgets.widgets(widgets::WidgetType::Affine).back(), 0.2);
    bool sawProgress = false;
    QTimer probe;
    connect(&probe, &QTimer::timeout, [&] { sawProgress = sawProgress || w.findChild<QWidget*>("embedProgress") != nullptr; });
    probe.start(0);
    action(w, "actionAttach")->trigger();
    probe.stop();
    MainWindow::setBackgroundEmbedPoints(saved);
    QVERIFY(sawProgress);
    QCOMPARE(w.scene().latticesDeforming(sphere).size(), std::size_t(1));
    // The embedding made in the worker gives the points the model gives.
    scenes::SceneDeformer model;
    model.update(w.scene());
    model.finishGesture(w.scene());
    QVERIFY(maxDifference(w.deformer().points(sphere), model.points(sphere)) < 1e-12);
    QVERIFY(maxDifference(w.deformer().points(sphere), w.scene().objects().front().mesh.points) > 0.05);
    action(w, "actionUndo")->trigger();
    QVERIFY(w.scene().attachments().empty());
  }

  void aGlyphIsReplacedByAPartFromThePropertyPanel() {
    MainWindow& w = *window_;
    const auto created = buildSphereWithWidgets(w, {flat(1, 1, 2)});
    QCOMPARE(created.size(), std::size_t(1));
    clickRow(w, QString::fromStdString(w.scene().widgets.name(created[0])));
    auto* glyph = w.findChild<QComboBox*>("glyph");
    QVERIFY(glyph != nullptr);
    const QImage before = w.view()->grabFramebuffer();
    glyph->setCurrentIndex(glyph->findText("crank"));
    QCOMPARE(w.scene().widgets.glyph(created[0]).shape, std::string("crank"));
    QVERIFY(w.view()->grabFramebuffer() != before);  // the part is drawn instead of the arrow
    action(w, "actionUndo")->trigger();
    QVERIFY(w.scene().widgets.glyph(created[0]).shape != "crank");
  }

  void altDragSlidesTheLatticeOverTheObject() {
    MainWindow& w = *window_;
    QCOMPARE(buildSphereWithWidgets(w, {}).size(), std::size_t(0));
    const std::string sphere = w.scene().objects().front().name;
    const WidgetId lattice = w.scene().widgets.roots().front();
    const Eigen::MatrixX3d before = w.deformer().points(sphere);
    const Eigen::MatrixX3d latticeBefore = w.scene().widgets.worldControlPoints(lattice);
    const QPoint a = toWidget(w, Eigen::Vector3d::Zero());
    const QPoint b = a + QPoint(60, 0);
    sendMouse(w.view(), QEvent::MouseButtonPress, a, Qt::LeftButton, Qt::LeftButton, Qt::AltModifier);
    for (int step = 1; step <= 5; ++step)
      sendMouse(w.view(), QEvent::MouseMove, a + (b - a) * step / 5, Qt::NoButton, Qt::LeftButton, Qt::AltModifier);
    sendMouse(w.view(), QEvent::MouseButtonRelease, b, Qt::LeftButton, Qt::NoButton, Qt::AltModifier);
    const Eigen::RowVector3d shift = w.scene().widgets.worldControlPoints(lattice).row(0) - latticeBefore.row(0);
    QVERIFY(shift.norm() > 0.1);
    QVERIFY(maxDifference(w.scene().widgets.worldControlPoints(lattice), latticeBefore.rowwise() + shift) < 1e-9);
    // Moving a lattice's frame moves its rest lattice too (Kuriyama 1996, sec. 6.2.3): the object is re-embedded
    // and, with the control points at rest, stays where it was.
    QVERIFY(maxDifference(w.deformer().points(sphere), before) < 1e-9);
    action(w, "actionUndo")->trigger();
    QVERIFY(maxDifference(w.scene().widgets.worldControlPoints(lattice), latticeBefore) < 1e-12);
  }

  void aWidgetFileSavedThroughTheUiOpensWithTheSameControlPoints() {
    MainWindow& w = *window_;
    w.openScene(FFDKIT_SOURCE_DIR "/scenes/examples/default");
    w.view()->grabFramebuffer();
    const WidgetId pull = w.scene().widgets.find("pull");
    dragArrow(w, pull, 0.15);  // from the file's 0 (it stores frame 0, the rest pose)
    QVERIFY(std::abs(w.scene().widgets.variation(pull) - 0.15) < 0.02);

    QTemporaryDir dir;
    const QString path = dir.filePath("tool.json");
    triggerWithFile(w, "actionSaveWidgetFile", path);
    QVERIFY(QFileInfo::exists(path));

    MainWindow other;
    other.show();
    QVERIFY(QTest::qWaitForWindowExposed(&other));
    triggerWithFile(other, "actionOpenWidgetFile", path);
    const auto& a = w.scene().widgets;
    const auto& b = other.scene().widgets;
    QCOMPARE(b.widgets(widgets::WidgetType::Lattice).size(), a.widgets(widgets::WidgetType::Lattice).size());
    for (WidgetId lattice : a.widgets(widgets::WidgetType::Lattice)) {
      const WidgetId same = b.find(a.name(lattice));
      QCOMPARE(b.worldControlPoints(same), a.worldControlPoints(lattice));
    }
    QCOMPARE(b.variation(b.find("pull")), a.variation(pull));
  }

  void latticesAreReorderedByDragAndDropInTheOutliner() {
    MainWindow& w = *window_;
    triggerWithDialog(w, "actionNewLattice");
    triggerWithDialog(w, "actionNewLattice");
    const auto roots = w.scene().widgets.roots();
    QCOMPARE(roots.size(), std::size_t(2));
    const QString first = QString::fromStdString(w.scene().widgets.name(roots[0]));
    const QString second = QString::fromStdString(w.scene().widgets.name(roots[1]));
    clickRow(w, second);
    QTreeWidget* tree = w.outliner();
    QTreeWidgetItem* target = tree->findItems(first, Qt::MatchExactly | Qt::MatchRecursive).front();
    std::unique_ptr<QMimeData> data(tree->model()->mimeData(tree->selectionModel()->selectedIndexes()));
    const QPoint at = tree->visualItemRect(target).center();
    QDragEnterEvent enter(at, Qt::MoveAction, data.get(), Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(tree->viewport(), &enter);
    QDragMoveEvent move(at, Qt::MoveAction, data.get(), Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(tree->viewport(), &move);
    QDropEvent drop(QPointF(at), Qt::MoveAction, data.get(), Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(tree->viewport(), &drop);
    const auto reordered = w.scene().widgets.roots();
    QCOMPARE(reordered.size(), std::size_t(2));
    QVERIFY(reordered[0] == roots[1]);  // the pipeline now runs the second lattice first
    action(w, "actionUndo")->trigger();
    QVERIFY(w.scene().widgets.roots()[0] == roots[0]);
  }

  // File > Allow Files Outside a Scene's Folder: off, a scene naming "../cloud.xyz" is refused;
  // clicked on in the menu (and kept in the settings), the same scene opens.
  void meshesOutsideTheScenesFolderNeedThePreference() {
    QTemporaryDir dir;
    std::ofstream(dir.filePath("cloud.xyz").toStdString()) << "0 0 0\n1 0 0\n";
    std::filesystem::create_directories(dir.filePath("shared").toStdString());
    const std::filesystem::path scene = dir.filePath("shared/scene.json").toStdString();
    std::ofstream(scene) << R"({"format": "ffdkit-scene", "version": 1, "objects": [{"name": "c", "mesh": {"path": "../cloud.xyz"}}]})";
    QSettings().setValue("allowFilesOutsideSceneFolder", false);
    window_ = std::make_unique<MainWindow>();  // reads the preference
    MainWindow& fresh = *window_;
    fresh.show();
    QVERIFY(QTest::qWaitForWindowExposed(&fresh));
    QAction* allow = action(fresh, "actionAllowOutside");
    QVERIFY(!allow->isChecked());
    QVERIFY_EXCEPTION_THROWN(fresh.openScene(scene), std::runtime_error);
    // Open the File menu and click the preference.
    QMenu* fileMenu = nullptr;
    QAction* fileTitle = nullptr;
    for (QAction* a : fresh.menuBar()->actions())
      if (a->menu() != nullptr && a->menu()->actions().contains(allow)) fileTitle = a, fileMenu = a->menu();
    QVERIFY(fileMenu != nullptr);
    QTest::mouseClick(fresh.menuBar(), Qt::LeftButton, Qt::NoModifier, fresh.menuBar()->actionGeometry(fileTitle).center());
    QTRY_VERIFY(fileMenu->isVisible());
    QTest::mouseClick(fileMenu, Qt::LeftButton, Qt::NoModifier, fileMenu->actionGeometry(allow).center());
    QTRY_VERIFY(allow->isChecked());
    QVERIFY(QSettings().value("allowFilesOutsideSceneFolder").toBool());
    fresh.openScene(scene);
    QCOMPARE(fresh.scene().objects().front().mesh.points.rows(), Eigen::Index(2));
    QSettings().setValue("allowFilesOutsideSceneFolder", false);
  }

  void droppedFilesOpenByKind() {
    MainWindow& w = *window_;
    QTemporaryDir dir;
    // A mesh file is imported as an object.
    scenes::MeshData mesh;
    mesh.points.resize(3, 3);
    mesh.points << 0, 0, 0, 1, 0, 0, 0, 1, 0;
    mesh.triangles.resize(1, 3);
    mesh.triangles << 0, 1, 2;
    const QString obj = dir.filePath("triangle.obj");
    scenes::writeMesh(obj.toStdString(), mesh);
    auto drop = [&](const QString& path) {
      QMimeData data;
      data.setUrls({QUrl::fromLocalFile(path)});
      const QPoint at(w.width() / 2, w.height() / 2);
      QDragEnterEvent enter(at, Qt::CopyAction, &data, Qt::LeftButton, Qt::NoModifier);
      QApplication::sendEvent(&w, &enter);
      QVERIFY(enter.isAccepted());
      QDropEvent dropped(QPointF(at), Qt::CopyAction, &data, Qt::LeftButton, Qt::NoModifier);
      QApplication::sendEvent(&w, &dropped);
    };
    drop(obj);
    QCOMPARE(w.scene().objects().size(), std::size_t(1));
    QCOMPARE(w.scene().objects().front().name, std::string("triangle"));
    QCOMPARE(w.scene().objects().front().mesh.points.rows(), Eigen::Index(3));
    // A widget file replaces the widgets; a scene opens.
    widgets::WidgetModel tool;
    tool.addLattice("dropped", Eigen::Vector3i(2, 3, 4));
    const QString json = dir.filePath("tool.json");
    scenes::writeWidgetFile(json.toStdString(), tool);
    drop(json);
    QCOMPARE(w.scene().objects().size(), std::size_t(1));
    QCOMPARE(w.scene().widgets.counts(w.scene().widgets.find("dropped")), Eigen::Vector3i(2, 3, 4));
    // The widget file's lattice went onto the only object.
    QCOMPARE(w.scene().attachments().size(), std::size_t(1));
    QVERIFY(w.scene().attachments().front().objects == std::vector<scenes::ObjectId>{w.scene().objectId("triangle")});
    {
      // A scene replaces the modified document: asked first (Discard).
      ffdkit::app::testing::ModalAnswers discard({[](QWidget* modal) {
        auto* box = qobject_cast<QMessageBox*>(modal);
        QVERIFY(box != nullptr);
        QTest::mouseClick(box->button(QMessageBox::Discard), Qt::LeftButton);
      }});
      drop(FFDKIT_SOURCE_DIR "/scenes/examples/vise/scene.json");
      QCOMPARE(discard.answered(), 1);
    }
    QVERIFY(w.scene().widgets.widgets(widgets::WidgetType::Affine).size() >= 2);
  }

  void zebraAndCombAreToggledFromTheViewMenuAndUndone() {
    MainWindow& w = *window_;
    auto stripePixels = [](const QImage& image, const Eigen::Vector3d& colour, double tolerance) {
      long n = 0;
      for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
          const QColor c = image.pixelColor(x, y);
          n += (Eigen::Vector3d(c.redF(), c.greenF(), c.blueF()) - colour).norm() < tolerance;
        }
      return n;
    };
    w.openScene(FFDKIT_SOURCE_DIR "/scenes/examples/default");
    const QImage shaded = w.view()->grabFramebuffer();
    QAction* zebra = action(w, "actionZebra");
    QVERIFY(zebra->isCheckable() && !zebra->isChecked());
    zebra->trigger();
    QVERIFY(zebra->isChecked());
    QCOMPARE(w.scene().objects().front().display.surfaceStyle, scenes::SurfaceStyle::Zebra);
    const QImage striped = w.view()->grabFramebuffer();
    QVERIFY(striped != shaded);
    const long dark = stripePixels(striped, app::kZebraDark, 0.1), light = stripePixels(striped, app::kZebraLight, 0.1);
    qInfo("zebra: %ld dark and %ld light stripe pixels (shaded: %ld, %ld)", dark, light,
          stripePixels(shaded, app::kZebraDark, 0.1), stripePixels(shaded, app::kZebraLight, 0.1));
    QVERIFY(dark > 1000 && light > 1000);
    // Shaded: a few dark pixels at the unlit rim at most, no light stripes.
    QVERIFY(stripePixels(shaded, app::kZebraDark, 0.1) + stripePixels(shaded, app::kZebraLight, 0.1) < (dark + light) / 20);
    QVERIFY(stripePixels(shaded, app::kZebraLight, 0.1) < light / 100);
    // Stripes follow a drag step (the deformed normals).
    const WidgetId arrow = w.scene().widgets.widgets(widgets::WidgetType::Affine).front();
    dragArrow(w, arrow, 0.3);
    QVERIFY(w.view()->grabFramebuffer() != striped);
    sendMouse(w.view(), QEvent::MouseMove, QPoint(2, 2), Qt::NoButton, Qt::NoButton);  // no hovered arrow
    action(w, "actionUndo")->trigger();  // the drag
    w.controller().clearSelection();      // the dragged arrow was selected
    QCOMPARE(w.view()->grabFramebuffer(), striped);
    action(w, "actionUndo")->trigger();  // the zebra
    QVERIFY(!zebra->isChecked());
    QCOMPARE(w.scene().objects().front().display.surfaceStyle, scenes::SurfaceStyle::Shaded);
    QCOMPARE(w.view()->grabFramebuffer(), shaded);

    w.openScene(FFDKIT_SOURCE_DIR "/scenes/examples/qi-interpolate");
    scenes::Scene plain = w.scene();
    for (const scenes::SceneObject& o : w.scene().objects()) {
      scenes::DisplaySettings look = o.display;
      look.curvatureComb = false;
      plain.setObjectDisplay(o.name, look);
    }
    w.setScene(plain);
    const QImage bare = w.view()->grabFramebuffer();
    QAction* comb = action(w, "actionCurvatureComb");
    QVERIFY(!comb->isChecked());
    comb->trigger();
    QVERIFY(comb->isChecked());
    const QImage combed = w.view()->grabFramebuffer();
    const long before = stripePixels(bare, app::kCombColour, 0.15), after = stripePixels(combed, app::kCombColour, 0.15);
    qInfo("comb pixels: %ld off, %ld on", before, after);
    QVERIFY(after > before + 500);
    action(w, "actionUndo")->trigger();
    QVERIFY(!comb->isChecked());
    QCOMPARE(w.view()->grabFramebuffer(), bare);
  }

  void stripeCountAndCombAreEditedInThePropertyPanel() {
    MainWindow& w = *window_;
    w.openScene(FFDKIT_SOURCE_DIR "/scenes/examples/sigma-spline-surface");
    QCOMPARE(w.scene().objects().front().display.surfaceStyle, scenes::SurfaceStyle::Zebra);
    QVERIFY(action(w, "actionZebra")->isChecked());
    clickRow(w, "torus");
    auto* stripes = w.findChild<QSpinBox*>("zebraStripes");
    QVERIFY(stripes != nullptr && stripes->isEnabled());
    QCOMPARE(stripes->value(), w.scene().objects().front().display.zebraStripes);
    const QImage before = w.view()->grabFramebuffer();
    stripes->setValue(3);
    QCOMPARE(w.scene().objects().front().display.zebraStripes, 3);
    QVERIFY(w.view()->grabFramebuffer() != before);
    auto* style = w.findChild<QComboBox*>("surfaceStyle");
    QVERIFY(style != nullptr);
    style->setCurrentIndex(0);
    QCOMPARE(w.scene().objects().front().display.surfaceStyle, scenes::SurfaceStyle::Shaded);
    QVERIFY(!action(w, "actionZebra")->isChecked());
    action(w, "actionUndo")->trigger();
    action(w, "actionUndo")->trigger();
    QCOMPARE(w.view()->grabFramebuffer(), before);

    w.openScene(FFDKIT_SOURCE_DIR "/scenes/examples/qi-interpolate");
    clickRow(w, "qi-curve");
    auto* comb = w.findChild<QCheckBox*>("curvatureComb");
    QVERIFY(comb != nullptr && comb->isChecked());
    auto* scale = w.findChild<QDoubleSpinBox*>("combScale");
    QVERIFY(scale != nullptr);
    const QImage combed = w.view()->grabFramebuffer();
    scale->setValue(2.0 * scale->value());
    QCOMPARE(w.scene().objects().front().display.combScale, 0.3);
    QVERIFY(w.view()->grabFramebuffer() != combed);
  }

  void aCurveIsSwitchedToALineInThePropertyPanelAndUndone() {
    MainWindow& w = *window_;
    w.openScene(FFDKIT_SOURCE_DIR "/scenes/examples/g3-curve");
    const scenes::SceneObject& curve = w.scene().objects().front();
    QVERIFY(curve.mesh.segments.rows() > 0 && curve.mesh.triangles.rows() == 0);
    QCOMPARE(curve.display.curveStyle, scenes::CurveStyle::Tube);
    clickRow(w, QString::fromStdString(curve.name));
    auto* style = panelControl<QComboBox>(w, "curveStyle");
    QVERIFY(style != nullptr);
    QCOMPARE(style->currentText(), QString("tube"));
    QVERIFY(panelControl<QComboBox>(w, "surfaceStyle") == nullptr);  // a curve has no surface look
    const QString undoText = action(w, "actionUndo")->text();
    const QImage tube = w.view()->grabFramebuffer();
    style->setCurrentIndex(style->findText("line"));
    QCOMPARE(w.scene().objects().front().display.curveStyle, scenes::CurveStyle::Line);
    QVERIFY(action(w, "actionUndo")->text() != undoText);  // one undoable command
    const QImage line = w.view()->grabFramebuffer();
    QCOMPARE(line.size(), tube.size());
    long changed = 0;
    for (int y = 0; y < tube.height(); ++y)
      for (int x = 0; x < tube.width(); ++x) changed += tube.pixel(x, y) != line.pixel(x, y);
    qInfo("curve as a line: %ld of %lld pixels changed", changed, static_cast<long long>(tube.width()) * tube.height());
    QVERIFY(changed > 500);
    action(w, "actionUndo")->trigger();
    QCOMPARE(w.scene().objects().front().display.curveStyle, scenes::CurveStyle::Tube);
    QCOMPARE(action(w, "actionUndo")->text(), undoText);
    QCOMPARE(w.view()->grabFramebuffer(), tube);
  }

  void eachSampleSceneShowsItsObject() {
    MainWindow& w = *window_;
    int scenesSeen = 0;
    for (const auto& folder : std::filesystem::directory_iterator(FFDKIT_SOURCE_DIR "/scenes/examples")) {
      if (!std::filesystem::exists(folder.path() / "scene.json")) continue;
      ++scenesSeen;
      const QString name = QString::fromStdString(folder.path().filename().string());
      w.openScene(folder.path());
      const QImage shot = w.view()->grabFramebuffer();
      QVERIFY(!shot.isNull());
      const scenes::Scene full = w.scene();
      // For each object: the same view without it; the pixels that differ are the object's.
      for (std::size_t i = 0; i < full.objects().size(); ++i) {
        const scenes::SceneObject& object = full.objects()[i];
        if (!object.display.visible) continue;
        scenes::Scene hidden = full;
        scenes::DisplaySettings look = object.display;
        look.visible = false;
        hidden.setObjectDisplay(object.name, look);
        w.setScene(hidden);
        const QImage bare = w.view()->grabFramebuffer();
        QCOMPARE(bare.size(), shot.size());
        long differing = 0, striped = 0;
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        for (int y = 0; y < shot.height(); ++y)
          for (int x = 0; x < shot.width(); ++x) {
            const QColor a = shot.pixelColor(x, y), b = bare.pixelColor(x, y);
            if (std::abs(a.red() - b.red()) + std::abs(a.green() - b.green()) + std::abs(a.blue() - b.blue()) < 30)
              continue;
            ++differing;
            const Eigen::Vector3d rgb(a.redF(), a.greenF(), a.blueF());
            if ((rgb - app::kZebraDark).norm() < 0.1 || (rgb - app::kZebraLight).norm() < 0.1) ++striped;
            if (object.display.curvatureComb && (rgb - app::kCombColour).norm() < 0.15) continue;  // the comb
            sum += rgb;
          }
        const double share = double(differing) / (double(shot.width()) * shot.height());
        const QString what = name + "/" + QString::fromStdString(object.name);
        qInfo("%s: object pixels %.2f %%", qPrintable(what), 100.0 * share);
        // Surfaces cover percents of the view; a curve (a tube) less.
        const bool curve = object.mesh.triangles.rows() == 0;
        QVERIFY2(share > (curve ? 0.002 : 0.01), qPrintable(QString("%1: object covers only %2 of the view").arg(what).arg(share)));
        if (object.display.surfaceStyle == scenes::SurfaceStyle::Zebra && !curve) {
          // Zebra: the object's pixels are the two stripe colours (edges and lattice lines aside).
          QVERIFY2(striped > 0.8 * differing, qPrintable(QString("%1: %2 of %3 pixels striped").arg(what).arg(striped).arg(differing)));
          continue;
        }
        // Shaded, but the object's hue: the mean colour points the way of its display colour.
        const double cosine = sum.normalized().dot(object.display.color.normalized());
        QVERIFY2(cosine > 0.95, qPrintable(QString("%1: mean object pixel is off its colour (%2)").arg(what).arg(cosine)));
      }
    }
    QVERIFY(scenesSeen >= 6);
  }

 private:
  std::unique_ptr<MainWindow> window_;
};

int main(int argc, char** argv) { return runGuiTest<MainWindowTest>(argc, argv); }

#include "main_window_test.moc"
