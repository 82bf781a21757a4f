// The outliner and the property panel follow the scene's change sets (issue 16): typing a
// variation, a drag, a rename update the fields and rows concerned in place and rebuild nothing;
// hover rebuilds nothing; selecting another item rebuilds the panel only. Real events under Xvfb;
// the widgets' own counters (Outliner::stats, PropertyPanel::stats) and item pointers that stay
// the same show what was rebuilt.
#include <QDoubleSpinBox>
#include <QLabel>
#include <QLineEdit>
#include <QTreeWidgetItemIterator>

#include <vector>

#include "gui_test_support.h"
#include "outliner.h"
#include "property_panel.h"

using namespace ffdkit;
using namespace ffdkit::app::testing;
using app::MainWindow;
using app::Outliner;
using app::PropertyPanel;

namespace {

std::vector<QTreeWidgetItem*> rows(QTreeWidget* tree) {
  std::vector<QTreeWidgetItem*> out;
  for (QTreeWidgetItemIterator it(tree); *it; ++it) out.push_back(*it);
  return out;
}

// Types `text` into the rename dialog and presses Enter.
ModalAnswers::Handler typeName(const QString& text) {
  return [text](QWidget* modal) {
    auto* edit = modal->findChild<QLineEdit*>();
    QVERIFY(edit != nullptr);
    edit->selectAll();
    QTest::keyClicks(edit, text);
    QTest::keyClick(edit, Qt::Key_Return);
  };
}

}  // namespace

class PanelUpdatesGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    window_ = startWindow(QSize(1200, 800), StartSettings::Kept, kExamples / "default");
    QVERIFY(window_ != nullptr);
  }
  void cleanup() { window_.reset(); }

  void typingAVariationUpdatesItsFieldAndRebuildsNothing() {
    MainWindow& w = *window_;
    clickRow(w, "pull");
    const widgets::WidgetId pull = w.scene().widgets.find("pull");
    auto* variation = panel().findChild<QDoubleSpinBox*>("variation");
    QVERIFY(variation != nullptr);
    const std::vector<QTreeWidgetItem*> before = rows(w.outliner());
    const Outliner::Stats tree = outliner().stats();
    const PropertyPanel::Stats fields = panel().stats();

    QTest::mouseDClick(variation->findChild<QLineEdit*>(), Qt::LeftButton);
    QTest::keyClick(variation, Qt::Key_A, Qt::ControlModifier);
    QTest::keyClicks(variation, "0.3");
    QTest::keyClick(variation, Qt::Key_Return);
    QCOMPARE(w.scene().widgets.variation(pull), 0.3);

    QCOMPARE(panel().findChild<QDoubleSpinBox*>("variation"), variation);
    QCOMPARE(panel().stats().rebuilds, fields.rebuilds);
    QCOMPARE(panel().stats().fieldsUpdated, fields.fieldsUpdated);  // it shows what was typed
    QCOMPARE(outliner().stats().rebuilds, tree.rebuilds);
    QCOMPARE(outliner().stats().rowsUpdated, tree.rowsUpdated);
    QVERIFY(rows(w.outliner()) == before);
  }

  void aDragUpdatesOneFieldInPlace() {
    MainWindow& w = *window_;
    clickRow(w, "pull");
    const widgets::WidgetId pull = w.scene().widgets.find("pull");
    auto* variation = panel().findChild<QDoubleSpinBox*>("variation");
    QVERIFY(variation != nullptr);
    const double start = w.scene().widgets.variation(pull);
    const std::vector<QTreeWidgetItem*> before = rows(w.outliner());
    const Outliner::Stats tree = outliner().stats();
    const PropertyPanel::Stats fields = panel().stats();

    dragArrow(w, pull, 0.2);
    const double now = w.scene().widgets.variation(pull);
    QVERIFY2(std::abs(now - start - 0.2) < 0.02, qPrintable(QString::number(now - start)));
    QCOMPARE(panel().findChild<QDoubleSpinBox*>("variation"), variation);
    QVERIFY(std::abs(variation->value() - now) <= 0.5e-4);  // 4 decimals shown
    QCOMPARE(panel().stats().rebuilds, fields.rebuilds);
    QCOMPARE(panel().stats().fieldsUpdated, fields.fieldsUpdated + 1);  // the variation, nothing else
    QCOMPARE(outliner().stats().rebuilds, tree.rebuilds);
    QVERIFY(rows(w.outliner()) == before);
  }

  void renamingALatticeRewritesTheRowsShowingIt() {
    MainWindow& w = *window_;
    clickRow(w, "lattice");
    const widgets::WidgetId lattice = w.scene().widgets.find("lattice");
    const std::vector<QTreeWidgetItem*> before = rows(w.outliner());
    QTreeWidgetItem* own = outliner().itemFor({app::OutlinerEntry::Kind::Widget, {}, lattice, {}});
    QVERIFY(own != nullptr);
    const Outliner::Stats tree = outliner().stats();
    const PropertyPanel::Stats fields = panel().stats();
    {
      ModalAnswers answers({typeName("cage")});
      pressKey(w, Qt::Key_F2);
      QCOMPARE(answers.answered(), 1);
    }
    QCOMPARE(w.scene().widgets.name(lattice), std::string("cage"));
    // The same rows: the lattice's own and the "deformed by" row under the sphere say "cage".
    QVERIFY(rows(w.outliner()) == before);
    QCOMPARE(outliner().stats().rebuilds, tree.rebuilds);
    QCOMPARE(outliner().stats().rowsUpdated, tree.rowsUpdated + 2);
    QCOMPARE(own->text(0), QString("cage"));
    QCOMPARE(w.outliner()->findItems("cage", Qt::MatchExactly | Qt::MatchRecursive).size(), 2);
    QVERIFY(w.outliner()->findItems("lattice", Qt::MatchExactly | Qt::MatchRecursive).isEmpty());
    // The panel's name label, nothing else.
    QCOMPARE(panel().stats().rebuilds, fields.rebuilds);
    QCOMPARE(panel().stats().fieldsUpdated, fields.fieldsUpdated + 1);
    bool shown = false;
    for (const QLabel* label : panel().findChildren<QLabel*>()) shown = shown || label->text() == "cage";
    QVERIFY(shown);
    // Undo gives the name back everywhere.
    pressKey(w, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(w.scene().widgets.name(lattice), std::string("lattice"));
    QCOMPARE(w.outliner()->findItems("lattice", Qt::MatchExactly | Qt::MatchRecursive).size(), 2);
    QVERIFY(w.outliner()->findItems("cage", Qt::MatchExactly | Qt::MatchRecursive).isEmpty());
  }

  void hoverAndSelectionRebuildNoRow() {
    MainWindow& w = *window_;
    clickRow(w, "pull");
    const widgets::WidgetId pull = w.scene().widgets.find("pull");
    const std::vector<QTreeWidgetItem*> before = rows(w.outliner());
    const Outliner::Stats tree = outliner().stats();
    const PropertyPanel::Stats fields = panel().stats();
    // Hover over the arrow and off it.
    const widgets::WidgetFrame f = w.scene().widgets.affineFrame(pull);
    hover(w, toWidget(w, f.frame.translation() + 0.6 * f.size * f.frame.linear().col(0)));
    hover(w, QPoint(5, 5));
    QCOMPARE(panel().stats().rebuilds, fields.rebuilds);
    QCOMPARE(panel().stats().fieldsUpdated, fields.fieldsUpdated);
    // The same row again: nothing; another row: the panel shows it, the outliner keeps its rows.
    clickRow(w, "pull");
    QCOMPARE(panel().stats().rebuilds, fields.rebuilds);
    clickRow(w, "top");
    QCOMPARE(panel().stats().rebuilds, fields.rebuilds + 1);
    QCOMPARE(outliner().stats().rebuilds, tree.rebuilds);
    QCOMPARE(outliner().stats().rowsUpdated, tree.rowsUpdated);
    QVERIFY(rows(w.outliner()) == before);
  }

 private:
  Outliner& outliner() { return *static_cast<Outliner*>(window_->outliner()); }
  PropertyPanel& panel() { return *window_->findChild<PropertyPanel*>("propertyPanel"); }

  std::unique_ptr<MainWindow> window_;
};

int main(int argc, char** argv) { return runGuiTest<PanelUpdatesGuiTest>(argc, argv); }

#include "panel_updates_gui_test.moc"
