// Attaching a lattice to a large object in the real window (Xvfb): the embedding runs in a
// worker behind a progress dialog that shows how far it is, and Cancel stops it and leaves the
// scene as it was.
#include <QApplication>
#include <QProgressDialog>
#include <QPushButton>
#include <QTest>
#include <QTimer>

#include <algorithm>

#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "gui_test_support.h"

using namespace ffdkit;
using app::MainWindow;
using namespace ffdkit::app::testing;

class EmbedProgressGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    window_ = startWindow(QSize());
    QVERIFY(window_ != nullptr);
  }
  void cleanup() { window_.reset(); }

  void theProgressBarCountsUpAndCancelLeavesTheSceneAsItWas() {
    MainWindow& w = *window_;
    // A fine sphere in a cylindrical lattice (EFFD): Newton embedding, about half a million points.
    scenes::PrimitiveOptions fine;
    fine.resolution = 1000;
    const std::string sphere = w.controller().addPrimitive(fine);
    const Eigen::Index points = w.scene().findObject(sphere)->mesh.points.rows();
    QVERIFY(points > 400000);
    app::NewLatticeOptions options;
    options.cylindrical = true;
    const widgets::WidgetId lattice = w.controller().newLattice(options);
    w.controller().addAffineAtPoint({lattice, 5}, widgets::AffineKind::Translate);
    w.controller().setVariation(w.scene().widgets.widgets(widgets::WidgetType::Affine).back(), 0.1);
    QVERIFY(MainWindow::backgroundEmbedPoints() <= points);
    const std::size_t commands = w.commands().position();

    // Watch the dialog; press Cancel once it shows a value strictly between 0 and the end.
    std::vector<int> seen;
    int maximum = 0;
    bool pressedCancel = false;
    QTimer probe;
    connect(&probe, &QTimer::timeout, [&] {
      auto* dialog = w.findChild<QProgressDialog*>("embedProgress");
      if (dialog == nullptr || !dialog->isVisible()) return;
      maximum = dialog->maximum();
      seen.push_back(dialog->value());
      if (!pressedCancel && dialog->value() > 0 && dialog->value() < dialog->maximum()) {
        pressedCancel = true;
        auto* cancel = dialog->findChild<QPushButton*>();
        QVERIFY(cancel != nullptr);
        QTest::mouseClick(cancel, Qt::LeftButton);
      }
    });
    probe.start(5);
    const bool attached = w.attachLattice(lattice, sphere);
    probe.stop();
    QVERIFY2(pressedCancel, qPrintable(QString("progress values seen: %1").arg(seen.size())));
    QCOMPARE(maximum, 1000);  // a determinate bar
    QVERIFY(!attached);
    QVERIFY(w.scene().attachments().empty());
    QCOMPARE(w.commands().position(), commands);
    QCOMPARE(w.deformer().points(sphere), w.scene().findObject(sphere)->mesh.points);
    QVERIFY(std::is_sorted(seen.begin(), seen.end()));

    // Again, to the end: the attached sphere is what the model gives.
    seen.clear();
    pressedCancel = true;  // watch only
    probe.start(5);
    QVERIFY(w.attachLattice(lattice, sphere));
    probe.stop();
    QCOMPARE(w.scene().latticesDeforming(sphere).size(), std::size_t(1));
    QCOMPARE(w.commands().position(), commands + 1);
    const auto expected = scenes::deformScene(w.scene());
    QVERIFY((w.deformer().points(sphere) - expected.at(sphere)).cwiseAbs().maxCoeff() < 1e-12);
    QVERIFY((w.deformer().points(sphere) - w.scene().findObject(sphere)->mesh.points).cwiseAbs().maxCoeff() > 0.01);
  }

 private:
  std::unique_ptr<MainWindow> window_;
};

int main(int argc, char** argv) { return runGuiTest<EmbedProgressGuiTest>(argc, argv); }

#include "embed_progress_gui_test.moc"
