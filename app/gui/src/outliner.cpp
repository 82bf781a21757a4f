#include "outliner.h"

#include <QDropEvent>
#include <QHeaderView>
#include <QMimeData>

#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::app {
namespace {

constexpr int kKindRole = Qt::UserRole;
constexpr int kIdRole = Qt::UserRole + 1;

OutlinerEntry entryOf(const QTreeWidgetItem* item) {
  OutlinerEntry e;
  const QVariant kind = item->data(0, kKindRole);
  if (!kind.isValid()) return e;
  e.kind = static_cast<OutlinerEntry::Kind>(kind.toInt());
  switch (e.kind) {
    case OutlinerEntry::Kind::Object: e.object = item->data(0, kIdRole).toString().toStdString(); break;
    case OutlinerEntry::Kind::Widget: e.widget.value = item->data(0, kIdRole).toUInt(); break;
    case OutlinerEntry::Kind::Binding: e.binding.value = item->data(0, kIdRole).toUInt(); break;
  }
  return e;
}

bool same(const OutlinerEntry& a, const OutlinerEntry& b) {
  return a.kind == b.kind && a.object == b.object && a.widget == b.widget && a.binding == b.binding;
}

QTreeWidgetItem* makeItem(QTreeWidgetItem* parent, const QString& text, const QString& type, OutlinerEntry::Kind kind,
                          const QVariant& id) {
  auto* item = new QTreeWidgetItem(parent, {text, type});
  item->setData(0, kKindRole, static_cast<int>(kind));
  item->setData(0, kIdRole, id);
  return item;
}

}  // namespace

Outliner::Outliner(QWidget* parent) : QTreeWidget(parent) {
  setObjectName("outliner");
  setColumnCount(2);
  setHeaderLabels({tr("Name"), tr("Type")});
  header()->setStretchLastSection(false);
  header()->setSectionResizeMode(0, QHeaderView::Stretch);
  header()->setSectionResizeMode(1, QHeaderView::ResizeToContents);
  setSelectionMode(QAbstractItemView::ExtendedSelection);
  setDragDropMode(QAbstractItemView::InternalMove);
  setAcceptDrops(true);
  viewport()->setAcceptDrops(true);
  connect(this, &QTreeWidget::itemSelectionChanged, this, [this] {
    if (!programmatic_) emit selectionEdited();
  });
}

void Outliner::rebuild(const scenes::Scene& scene) {
  const auto keep = selection();
  programmatic_ = true;
  clear();
  const auto& m = scene.widgets;
  auto* objects = new QTreeWidgetItem(this, {tr("Objects")});
  for (const auto& object : scene.objects) {
    auto* item = makeItem(objects, QString::fromStdString(object.name), tr("object"), OutlinerEntry::Kind::Object,
                          QString::fromStdString(object.name));
    for (widgets::WidgetId lattice : scene.latticesDeforming(object.name))
      new QTreeWidgetItem(item, {QString::fromStdString(m.name(lattice)), tr("deformed by")});
  }
  auto* tree = new QTreeWidgetItem(this, {tr("Widgets")});
  std::function<void(QTreeWidgetItem*, widgets::WidgetId)> addLattice = [&](QTreeWidgetItem* parent,
                                                                             widgets::WidgetId lattice) {
    const Eigen::Vector3i n = m.counts(lattice);
    auto* item = makeItem(parent, QString::fromStdString(m.name(lattice)),
                          tr("lattice %1x%2x%3").arg(n.x()).arg(n.y()).arg(n.z()), OutlinerEntry::Kind::Widget,
                          lattice.value);
    for (widgets::WidgetId cell : m.cellsOf(lattice)) {
      auto* cellItem = makeItem(item, QString::fromStdString(m.name(cell)),
                                tr("%1 cell").arg(QString::fromStdString(std::string(cellKindName(m.cellSpec(cell).kind)))),
                                OutlinerEntry::Kind::Widget, cell.value);
      for (widgets::WidgetId affine : m.affinesOf(cell))
        makeItem(cellItem, QString::fromStdString(m.name(affine)),
                 QString::fromStdString(std::string(affineKindName(m.affineKind(affine)))), OutlinerEntry::Kind::Widget,
                 affine.value);
      for (widgets::WidgetId child : m.children(lattice))
        if (m.parentCell(child) == cell) addLattice(cellItem, child);
    }
  };
  for (widgets::WidgetId root : m.roots()) addLattice(tree, root);
  for (widgets::WidgetId affine : m.widgets(widgets::WidgetType::Affine))
    if (!m.attachedCell(affine))
      makeItem(tree, QString::fromStdString(m.name(affine)),
               tr("free %1").arg(QString::fromStdString(std::string(affineKindName(m.affineKind(affine))))),
               OutlinerEntry::Kind::Widget, affine.value);
  auto* bindings = new QTreeWidgetItem(this, {tr("Bindings")});
  for (widgets::BindingId id : m.bindings()) {
    const widgets::Binding& b = m.binding(id);
    makeItem(bindings,
             QString::fromStdString(m.name(b.from) + (b.oneWay ? " -> " : " <-> ") + m.name(b.to)),
             QString::fromStdString(std::string(bindingKindName(b.kind))), OutlinerEntry::Kind::Binding, id.value);
  }
  for (auto* top : {objects, tree, bindings}) top->setFlags(top->flags() & ~Qt::ItemIsSelectable & ~Qt::ItemIsDragEnabled);
  expandAll();
  programmatic_ = false;
  select(keep);
}

void Outliner::select(const std::vector<OutlinerEntry>& entries) {
  programmatic_ = true;
  clearSelection();
  for (const auto& e : entries)
    if (auto* item = itemFor(e)) item->setSelected(true);
  programmatic_ = false;
}

std::vector<OutlinerEntry> Outliner::selection() const {
  std::vector<OutlinerEntry> out;
  for (const QTreeWidgetItem* item : selectedItems())
    if (item->data(0, kKindRole).isValid()) out.push_back(entryOf(item));
  return out;
}

QTreeWidgetItem* Outliner::itemFor(const OutlinerEntry& entry) const {
  for (QTreeWidgetItemIterator it(const_cast<Outliner*>(this)); *it; ++it)
    if ((*it)->data(0, kKindRole).isValid() && same(entryOf(*it), entry)) return *it;
  return nullptr;
}

// Rows of this tree only (its own mime type); dropEvent decides what a drop may do.
void Outliner::dragEnterEvent(QDragEnterEvent* event) {
  if (event->mimeData()->hasFormat(mimeTypes().front())) {
    event->acceptProposedAction();
  } else {
    event->ignore();
  }
}

void Outliner::dragMoveEvent(QDragMoveEvent* event) {
  if (event->mimeData()->hasFormat(mimeTypes().front())) {
    event->acceptProposedAction();
  } else {
    event->ignore();
  }
}

void Outliner::dropEvent(QDropEvent* event) {
  // Only lattices move, and only among their siblings; the model decides, then we rebuild.
  QTreeWidgetItem* target = itemAt(event->position().toPoint());
  const auto moving = selection();
  event->ignore();
  if (target == nullptr || moving.size() != 1 || moving.front().kind != OutlinerEntry::Kind::Widget) return;
  const OutlinerEntry onto = entryOf(target);
  if (onto.kind != OutlinerEntry::Kind::Widget) return;
  QTreeWidgetItem* source = itemFor(moving.front());
  if (source == nullptr || source->parent() != target->parent() || source == target) return;
  QTreeWidgetItem* parent = target->parent();
  int position = 0;
  for (int i = 0; i < parent->childCount(); ++i) {
    if (parent->child(i) == target) break;
    if (parent->child(i)->text(1).startsWith("lattice") && parent->child(i) != source) ++position;
  }
  emit siblingMoveRequested(moving.front().widget, position);
}

}  // namespace ffdkit::app
