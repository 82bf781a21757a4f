// 1,000 random edits of a scene's objects (add, remove, rename, look, attach, detach, variation,
// undo, redo) and selections clicked in the outliner, in the main window under Xvfb: after each,
// the view, the outliner and the property panel, which follow the change sets in place, show what
// ones built from scratch on the present scene show (the drawn actors' bounds, every row's text
// and selection, every field's value). Objects are held by id, so a rename keeps the view's actor,
// the outliner's row and its selection, and the panel showing the object.
#include <QAbstractButton>
#include <QAbstractSpinBox>
#include <QCheckBox>
#include <QComboBox>
#include <QLabel>
#include <QLineEdit>
#include <QTreeWidgetItemIterator>

#include <array>
#include <random>

#include <vtkActor.h>
#include <vtkActorCollection.h>
#include <vtkNew.h>
#include <vtkRenderer.h>

#include "ffdkit/interaction/interaction_controller.h"
#include "gui_test_support.h"
#include "outliner.h"
#include "property_panel.h"

using namespace ffdkit;
using namespace ffdkit::app::testing;
using app::MainWindow;
using app::Outliner;
using app::PropertyPanel;

namespace {

// The visible actors' bounds, sorted: what a view draws.
std::vector<std::array<double, 6>> drawnBounds(vtkRenderer* renderer) {
  std::vector<std::array<double, 6>> all;
  vtkActorCollection* actors = renderer->GetActors();
  actors->InitTraversal();
  while (vtkActor* actor = actors->GetNextActor()) {
    if (!actor->GetVisibility()) continue;
    std::array<double, 6> b{};
    actor->GetBounds(b.data());
    all.push_back(b);
  }
  std::sort(all.begin(), all.end());
  return all;
}

// Every row of a tree: depth, both texts, selected or not.
QStringList rowsOf(QTreeWidget* tree) {
  QStringList rows;
  for (QTreeWidgetItemIterator it(tree); *it; ++it) {
    int depth = 0;
    for (QTreeWidgetItem* up = (*it)->parent(); up; up = up->parent()) ++depth;
    rows << QString("%1|%2|%3|%4").arg(depth).arg((*it)->text(0), (*it)->text(1)).arg((*it)->isSelected());
  }
  return rows;
}

// Every control of a panel with its shown value, in creation order.
QStringList fieldsOf(const QWidget* panel) {
  QStringList fields;
  for (const QWidget* child : panel->findChildren<QWidget*>()) {
    if (child->isHidden() && child->parentWidget() == panel) continue;
    QString value;
    if (auto* label = qobject_cast<const QLabel*>(child)) value = label->text();
    else if (auto* line = qobject_cast<const QLineEdit*>(child)) value = line->text();
    else if (auto* spin = qobject_cast<const QAbstractSpinBox*>(child)) value = spin->text();
    else if (auto* combo = qobject_cast<const QComboBox*>(child)) value = combo->currentText();
    else if (auto* check = qobject_cast<const QCheckBox*>(child)) value = check->isChecked() ? "on" : "off";
    else if (auto* button = qobject_cast<const QAbstractButton*>(child)) value = button->text();
    else continue;
    fields << child->metaObject()->className() + QString(" ") + child->objectName() + "=" + value;
  }
  return fields;
}

}  // namespace

class ObjectEditsGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void aThousandRandomObjectEditsLeaveViewOutlinerAndPanelAsBuiltFromScratch() {
    auto window = openWindow(QSize(640, 480));
    QVERIFY(window != nullptr);
    MainWindow& w = *window;
    w.openScene(kExamples / "default");
    app::InteractionController& c = w.controller();
    auto& outliner = *static_cast<Outliner*>(w.outliner());
    auto& panel = *w.findChild<PropertyPanel*>("propertyPanel");
    std::mt19937 random(33);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    auto pickObject = [&]() -> std::string {
      const auto& objects = w.scene().objects();
      return objects[std::uniform_int_distribution<std::size_t>(0, objects.size() - 1)(random)].name;
    };
    int renames = 0, refused = 0;
    for (int step = 0; step < 1000; ++step) {
      const auto lattices = w.scene().widgets.roots();
      const auto affines = w.scene().widgets.widgets(widgets::WidgetType::Affine);
      try {
        switch (std::uniform_int_distribution<int>(0, 10)(random)) {
          case 0: {
            scenes::PrimitiveOptions primitive;
            primitive.kind = static_cast<scenes::PrimitiveKind>(std::uniform_int_distribution<int>(0, 2)(random));
            primitive.resolution = 6;
            primitive.placement = Eigen::Translation3d(3.0 * unit(random), 0.0, 0.0);
            c.addPrimitive(primitive);
            break;
          }
          case 1:
            if (w.scene().objects().size() > 1) c.removeObjects({pickObject()});
            break;
          case 2:
          case 3:
            c.renameObject(pickObject(), "object " + std::to_string(step));
            ++renames;
            break;
          case 4: {
            const std::string object = pickObject();
            scenes::DisplaySettings look = w.scene().findObject(object)->display;
            look.color = Eigen::Vector3d(unit(random), unit(random), unit(random));
            look.visible = unit(random) > 0.2;
            c.setDisplay({object}, {look});
            break;
          }
          case 5:
            if (!lattices.empty()) c.attachLattice(lattices[std::size_t(step) % lattices.size()], pickObject());
            break;
          case 6:
            if (!w.scene().attachments().empty()) {
              const scenes::Attachment& a = w.scene().attachments().back();
              c.detachLattice(a.lattice, w.scene().objectName(a.objects.front()));
            }
            break;
          case 7:
            if (!affines.empty()) c.setVariation(affines[std::size_t(step) % affines.size()], 0.4 * unit(random) - 0.2);
            break;
          case 8:
            if (w.commands().canUndo()) w.commands().undo();
            break;
          case 9:
            if (w.commands().canRedo()) w.commands().redo();
            break;
          case 10:
            clickRow(w, QString::fromStdString(pickObject()));  // a real click selects the object
            break;
        }
      } catch (const std::exception&) {
        ++refused;  // a refused edit (attaching twice, ...) leaves no trace
      }
      QCoreApplication::processEvents();
      QCoreApplication::sendPostedEvents(nullptr, QEvent::DeferredDelete);  // rows the panel let go

      // The view: what a view built from scratch on the present scene and deformer draws.
      vtkNew<vtkRenderer> renderer;
      app::SceneView fresh(renderer);
      fresh.setHighlights(c.highlights());
      fresh.show(w.scene(), w.deformer());
      QVERIFY2(drawnBounds(w.view()->renderer()) == drawnBounds(renderer), qPrintable(QString("view, step %1").arg(step)));

      // The outliner: a fresh one, rebuilt from the scene, with the same selection.
      Outliner rebuilt;
      rebuilt.rebuild(w.scene());
      rebuilt.select(outliner.selection());
      QCOMPARE(rowsOf(&outliner), rowsOf(&rebuilt));

      // The panel: a fresh one showing the outliner's selection.
      PropertyPanel built(c, w.scene());
      built.showSelection(outliner.selection());
      const QStringList shown = fieldsOf(&panel), expected = fieldsOf(&built);
      QVERIFY2(shown == expected, qPrintable(QString("panel, step %1:\n%2\n-- from scratch --\n%3")
                                                 .arg(step)
                                                 .arg(shown.join("\n"), expected.join("\n"))));
    }
    QVERIFY(renames > 100);
    QVERIFY(refused < 300);
  }
};

int main(int argc, char** argv) { return runGuiTest<ObjectEditsGuiTest>(argc, argv); }
#include "object_edits_gui_test.moc"
