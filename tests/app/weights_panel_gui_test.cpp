// A control point's weight typed in the property panel (real mouse and key events in the real
// window, Xvfb): the picked point of a lattice shows its weight; text that is no weight (letters,
// 0, a negative number, nan) is refused with a message under the field and changes nothing; a
// valid weight is one undo step, the lattice becomes rational, and the object's points equal what
// ffdkit-cli deform makes of the same points with the widget file the app saved; undo restores
// the polynomial lattice and the points. In the lattice's edit mode (Tab) the same field sets the
// weight of every selected point (clicked, Shift+clicked, box-selected): their common weight, or
// blank when they differ; one undo step per typed weight.
#include <QLabel>
#include <QLineEdit>
#include <QProcess>
#include <QTemporaryDir>
#include <QTest>

#include <filesystem>

#include "../cli/ffdkit_cli_path.h"
#include "ffdkit/meshio/mesh_io.h"
#include "fig62_steps.h"
#include "gui_test_support.h"

using namespace ffdkit;
using app::MainWindow;
using widgets::WidgetId;
using namespace ffdkit::app::testing;

namespace {

// Runs ffdkit-cli with `arguments`; its exit code (-1 if it crashed or did not finish).
int runCli(const QStringList& arguments, QString* output) {
  QProcess cli;
  cli.setProcessChannelMode(QProcess::MergedChannels);
  cli.start(QString::fromStdString(ffdkit::test::ffdkitCli()), arguments);
  if (!cli.waitForFinished(60000)) return -1;
  *output = QString::fromLocal8Bit(cli.readAll());
  return cli.exitStatus() == QProcess::NormalExit ? cli.exitCode() : -1;
}

// The shown control named `name` (a rebuilt panel's old rows may still wait for their deletion).
template <class T>
T* shownChild(MainWindow& w, const char* name) {
  for (T* child : w.findChildren<T*>(name))
    if (child->isVisible()) return child;
  return nullptr;
}

// Types `text` into the field as a user does: click into it, Ctrl+A, the keys, Enter.
void typeInto(QLineEdit* field, const QString& text) {
  QTest::mouseClick(field, Qt::LeftButton);
  QTest::keyClick(field, Qt::Key_A, Qt::ControlModifier);
  QTest::keyClicks(field, text);
  QTest::keyClick(field, Qt::Key_Return);
}

// The message label under a weight field (its sibling of that name).
QLabel* messageOf(MainWindow& w, QLineEdit* field) {
  for (QLabel* label : w.findChildren<QLabel*>(field->objectName() + "Message"))
    if (label->parentWidget() == field->parentWidget()) return label;
  return nullptr;
}

// The object's points as ffdkit-cli deform --widgets makes them with the widget file the window
// saves now (empty, with the reason in `failure`, if the CLI failed).
Eigen::MatrixX3d cliDeformed(MainWindow& w, scenes::ObjectId object, QString* failure) {
  QTemporaryDir folder;
  const std::filesystem::path dir = folder.path().toStdString();
  w.saveWidgetFile(dir / "tool.json");
  meshio::MeshData points;
  points.points = w.scene().findObject(object)->mesh.points;
  meshio::writeMesh(dir / "object.npy", points);
  QString output;
  const int code = runCli({"deform", "--widgets", QString::fromStdString((dir / "tool.json").string()),
                           QString::fromStdString((dir / "object.npy").string()), "-o",
                           QString::fromStdString((dir / "out.npy").string())},
                          &output);
  if (code != 0) {
    *failure = QString("exit %1: %2").arg(code).arg(output);
    return {};
  }
  return meshio::readMesh(dir / "out.npy").points;
}

// Where lattice point `index` is drawn in the view.
QPoint pixelOf(MainWindow& w, WidgetId lattice, Eigen::Index index) {
  return toWidget(w, w.scene().widgets.worldControlPoints(lattice).row(index).transpose());
}

// A rectangle of the view (corners `a`, `b`) that holds some points of `lattice` with a 3-pixel
// margin and has every other point at least 3 pixels outside, holding at least one point with
// weight `marked` and one without; the points it holds (sorted) in `inside`. False if none is found.
bool boxWithMixedWeights(MainWindow& w, WidgetId lattice, double marked, QPoint* a, QPoint* b,
                         std::vector<Eigen::Index>* inside) {
  const Eigen::VectorXd weights = w.scene().widgets.weights(lattice);
  const Eigen::Index n = weights.size();
  std::vector<QPoint> pixels;
  for (Eigen::Index i = 0; i < n; ++i) pixels.push_back(pixelOf(w, lattice, i));
  for (Eigen::Index p = 0; p < n; ++p)
    for (Eigen::Index q = 0; q < n; ++q) {
      if (weights[p] != marked || weights[q] == marked) continue;
      const QRect core = QRect(pixels[p], pixels[q]).normalized();
      const QRect box = core.adjusted(-6, -6, 6, 6);
      std::vector<Eigen::Index> held;
      bool clean = true, mixed[2] = {false, false};
      for (Eigen::Index i = 0; i < n; ++i) {
        const QPoint x = pixels[i];
        if (core.adjusted(-3, -3, 3, 3).contains(x)) {
          held.push_back(i);
          mixed[weights[i] == marked ? 0 : 1] = true;
        } else if (box.adjusted(-3, -3, 3, 3).contains(x)) {
          clean = false;  // too near the rectangle's edge to say
        }
      }
      if (!clean || !mixed[0] || !mixed[1] || held.size() > static_cast<std::size_t>(n / 2)) continue;
      *a = box.topLeft();
      *b = box.bottomRight();
      *inside = held;
      return true;
    }
  return false;
}

}  // namespace

class WeightsPanelGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    window_ = openWindow(QSize(1000, 760));
    QVERIFY(window_ != nullptr);
  }
  void cleanup() { window_.reset(); }

  void aTypedWeightMakesTheLatticeRationalAsTheCliDoes() {
    MainWindow& w = *window_;
    triggerWithDialog(w, "actionAddPrimitive");  // sphere1
    triggerWithDialog(w, "actionNewLattice");
    action(w, "actionAttach")->trigger();
    pressKey(w, Qt::Key_Home);
    const WidgetId lattice = w.scene().widgets.roots().front();
    const scenes::ObjectId sphere = w.scene().objectId("sphere1");
    const Eigen::MatrixX3d start = w.deformer().points(sphere);
    const Eigen::Index point = flat(2, 1, 2);  // the middle of the top face's +x edge
    click(w, toWidget(w, w.scene().widgets.worldControlPoints(lattice).row(point).transpose()));
    QVERIFY(w.controller().pickedPoint() && w.controller().pickedPoint()->index == point);
    QCoreApplication::processEvents();  // the panel's new rows are shown from the event loop
    auto* field = shownChild<QLineEdit>(w, "pointWeight");
    QVERIFY(field != nullptr);
    QCOMPARE(field->text(), QString("1"));
    QLabel* message = nullptr;
    for (QLabel* label : w.findChildren<QLabel*>("pointWeightMessage"))
      if (label->parentWidget() == field->parentWidget()) message = label;
    QVERIFY(message != nullptr && !message->isVisible());
    const std::size_t steps = w.commands().position();

    // Refused: the model is not touched, no undo step, the reason under the field.
    for (const char* bad : {"abc", "0", "-2", "nan", "inf"}) {
      typeInto(field, bad);
      QVERIFY2(message->isVisible(), bad);
      QVERIFY2(message->text().contains("weight"), qPrintable(message->text()));
      QVERIFY2(!w.scene().widgets.isRational(lattice), bad);
      QCOMPARE(w.commands().position(), steps);
    }
    QVERIFY(message->text().contains("finite") || message->text().contains("> 0"));

    typeInto(field, "3");
    QVERIFY(!message->isVisible());
    QCOMPARE(w.commands().position(), steps + 1);
    QVERIFY(w.scene().widgets.isRational(lattice));
    QCOMPARE(w.scene().widgets.weights(lattice)[point], 3.0);
    const Eigen::MatrixX3d weighted = w.deformer().points(sphere);
    QVERIFY((weighted - start).cwiseAbs().maxCoeff() > 1e-3);  // pulled towards the point ...
    // ... though no control point moved: the weight alone.
    QCOMPARE((w.scene().widgets.controlPoints(lattice) - w.scene().widgets.restPoints(lattice)).cwiseAbs().maxCoeff(), 0.0);

    // The CLI deforms the sphere's own points with the widget file the app saves.
    QTemporaryDir folder;
    QVERIFY(folder.isValid());
    const std::filesystem::path dir = folder.path().toStdString();
    w.saveWidgetFile(dir / "tool.json");
    meshio::MeshData points;
    points.points = w.scene().findObject(sphere)->mesh.points;
    meshio::writeMesh(dir / "sphere.npy", points);
    QString output;
    QCOMPARE(runCli({"deform", "--widgets", QString::fromStdString((dir / "tool.json").string()),
                     QString::fromStdString((dir / "sphere.npy").string()), "-o",
                     QString::fromStdString((dir / "out.npy").string())},
                    &output),
             0);
    const Eigen::MatrixX3d cli = meshio::readMesh(dir / "out.npy").points;
    QCOMPARE(cli.rows(), weighted.rows());
    const double worst = (cli - weighted).cwiseAbs().maxCoeff();
    QVERIFY2(worst <= 1e-12, qPrintable(QString("%1 (cli: %2)").arg(worst).arg(output)));

    action(w, "actionUndo")->trigger();
    QVERIFY(!w.scene().widgets.isRational(lattice));
    QCoreApplication::processEvents();
    QVERIFY(shownChild<QLineEdit>(w, "pointWeight") != nullptr);
    QCOMPARE(shownChild<QLineEdit>(w, "pointWeight")->text(), QString("1"));
    QVERIFY((w.deformer().points(sphere) - start).cwiseAbs().maxCoeff() <= 1e-14);
    action(w, "actionRedo")->trigger();
    QCOMPARE(w.scene().widgets.weights(lattice)[point], 3.0);
    QCoreApplication::processEvents();
    QCOMPARE(shownChild<QLineEdit>(w, "pointWeight")->text(), QString("3"));
  }

  void inTheEditModeTheSelectedPointsWeightIsTypedForAllOfThem() {
    MainWindow& w = *window_;
    triggerWithDialog(w, "actionAddPrimitive");  // sphere1
    triggerWithDialog(w, "actionNewLattice");
    action(w, "actionAttach")->trigger();
    pressKey(w, Qt::Key_Home);
    const WidgetId lattice = w.scene().widgets.roots().front();
    const scenes::ObjectId sphere = w.scene().objectId("sphere1");
    const Eigen::MatrixX3d start = w.deformer().points(sphere);
    pressKey(w, Qt::Key_Tab);
    QVERIFY(w.editController().editing());
    QCoreApplication::processEvents();
    auto* edited = shownChild<QLabel>(w, "editedPoints");
    QVERIFY(edited != nullptr);
    QVERIFY2(edited->text().contains("0 of 27 points"), qPrintable(edited->text()));
    QVERIFY(shownChild<QLineEdit>(w, "editWeight") == nullptr);  // nothing selected: no weight

    // One point clicked, two more Shift+clicked: their common weight.
    const std::vector<Eigen::Index> three = {flat(2, 1, 2), flat(0, 1, 2), flat(1, 2, 2)};
    clickPoint(w, lattice, three[0]);
    QCoreApplication::processEvents();
    QVERIFY(shownChild<QLineEdit>(w, "editWeight") != nullptr);
    QCOMPARE(shownChild<QLineEdit>(w, "editWeight")->text(), QString("1"));
    clickPoint(w, lattice, three[1], Qt::ShiftModifier);
    clickPoint(w, lattice, three[2], Qt::ShiftModifier);
    QCOMPARE(w.editController().points().count(), Eigen::Index(3));
    QCoreApplication::processEvents();
    QVERIFY(shownChild<QLabel>(w, "editedPoints")->text().contains("3 of 27 points"));
    auto* field = shownChild<QLineEdit>(w, "editWeight");
    QVERIFY(field != nullptr);
    QCOMPARE(field->text(), QString("1"));
    QLabel* message = messageOf(w, field);
    QVERIFY(message != nullptr && !message->isVisible());
    const std::size_t steps = w.commands().position();

    // Refused as outside the edit mode: nothing changes, the reason under the field.
    for (const char* bad : {"abc", "0", "-2", "nan", "inf"}) {
      typeInto(field, bad);
      QVERIFY2(message->isVisible(), bad);
      QVERIFY2(message->text().contains("weight"), qPrintable(message->text()));
      QVERIFY2(!w.scene().widgets.isRational(lattice), bad);
      QCOMPARE(w.commands().position(), steps);
    }

    // 2.5 for the three: one undo step; the other points keep 1.
    typeInto(field, "2.5");
    QVERIFY(!message->isVisible());
    QCOMPARE(w.commands().position(), steps + 1);
    Eigen::VectorXd expected = Eigen::VectorXd::Ones(27);
    for (Eigen::Index p : three) expected[p] = 2.5;
    QCOMPARE((w.scene().widgets.weights(lattice) - expected).cwiseAbs().maxCoeff(), 0.0);
    const Eigen::VectorXd threeWeighted = expected;
    const Eigen::MatrixX3d threePoints = w.deformer().points(sphere);
    QVERIFY((threePoints - start).cwiseAbs().maxCoeff() > 1e-3);

    // A box (B, then a drag) over points of both weights: the field is blank, their range shown.
    QPoint from, to;
    std::vector<Eigen::Index> boxed;
    QVERIFY(boxWithMixedWeights(w, lattice, 2.5, &from, &to, &boxed));
    pressKey(w, Qt::Key_B);
    dragPixels(w, from, to);
    QCOMPARE(w.editController().points().indices(), boxed);
    QCoreApplication::processEvents();
    field = shownChild<QLineEdit>(w, "editWeight");
    QVERIFY(field != nullptr);
    QCOMPARE(field->text(), QString());
    QVERIFY2(field->placeholderText() == "differ: 1 to 2.5", qPrintable(field->placeholderText()));

    // 4 for all of them: one undo step.
    typeInto(field, "4");
    QCOMPARE(w.commands().position(), steps + 2);
    for (Eigen::Index p : boxed) expected[p] = 4.0;
    QCOMPARE((w.scene().widgets.weights(lattice) - expected).cwiseAbs().maxCoeff(), 0.0);
    QCoreApplication::processEvents();
    QCOMPARE(shownChild<QLineEdit>(w, "editWeight")->text(), QString("4"));
    const Eigen::MatrixX3d weighted = w.deformer().points(sphere);
    // ... though no control point moved: the weights alone.
    QCOMPARE((w.scene().widgets.controlPoints(lattice) - w.scene().widgets.restPoints(lattice)).cwiseAbs().maxCoeff(), 0.0);

    // The CLI deforms the sphere's own points with the widget file the app saves: the same points.
    QString failure;
    const Eigen::MatrixX3d cli = cliDeformed(w, sphere, &failure);
    QVERIFY2(cli.rows() == weighted.rows(), qPrintable(failure));
    const double worst = (cli - weighted).cwiseAbs().maxCoeff();
    QVERIFY2(worst <= 1e-12, qPrintable(QString::number(worst)));

    // Undo: the three at 2.5 again, the field blank over the box; again: the polynomial lattice.
    action(w, "actionUndo")->trigger();
    QCOMPARE((w.scene().widgets.weights(lattice) - threeWeighted).cwiseAbs().maxCoeff(), 0.0);
    QVERIFY((w.deformer().points(sphere) - threePoints).cwiseAbs().maxCoeff() <= 1e-12);
    QCoreApplication::processEvents();
    QCOMPARE(shownChild<QLineEdit>(w, "editWeight")->text(), QString());
    action(w, "actionUndo")->trigger();
    QVERIFY(!w.scene().widgets.isRational(lattice));
    QVERIFY((w.deformer().points(sphere) - start).cwiseAbs().maxCoeff() <= 1e-12);
    QCoreApplication::processEvents();
    QCOMPARE(shownChild<QLineEdit>(w, "editWeight")->text(), QString("1"));
    // Redo, twice: the weights and the points the CLI made.
    action(w, "actionRedo")->trigger();
    action(w, "actionRedo")->trigger();
    QCOMPARE((w.scene().widgets.weights(lattice) - expected).cwiseAbs().maxCoeff(), 0.0);
    QVERIFY((w.deformer().points(sphere) - cli).cwiseAbs().maxCoeff() <= 1e-12);
    QVERIFY(w.editController().editing());
    QCoreApplication::processEvents();
    QCOMPARE(shownChild<QLineEdit>(w, "editWeight")->text(), QString("4"));
  }

 private:
  std::unique_ptr<MainWindow> window_;
};

int main(int argc, char** argv) { return runGuiTest<WeightsPanelGuiTest>(argc, argv); }

#include "weights_panel_gui_test.moc"
