// A control point's weight typed in the property panel (real mouse and key events in the real
// window, Xvfb): the picked point of a lattice shows its weight; text that is no weight (letters,
// 0, a negative number, nan) is refused with a message under the field and changes nothing; a
// valid weight is one undo step, the lattice becomes rational, and the object's points equal what
// ffdkit-cli deform makes of the same points with the widget file the app saved; undo restores
// the polynomial lattice and the points.
#include <QLabel>
#include <QLineEdit>
#include <QProcess>
#include <QTemporaryDir>
#include <QTest>

#include <filesystem>

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
  cli.start(FFDKIT_CLI, arguments);
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

 private:
  std::unique_ptr<MainWindow> window_;
};

int main(int argc, char** argv) { return runGuiTest<WeightsPanelGuiTest>(argc, argv); }

#include "weights_panel_gui_test.moc"
