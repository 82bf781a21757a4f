#include "outliner.h"

#include <set>

#include <QDropEvent>
#include <QHeaderView>
#include <QMimeData>

#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::app {
namespace {

constexpr int kKindRole = Qt::UserRole;
constexpr int kIdRole = Qt::UserRole + 1;
constexpr int kDeformedByRole = Qt::UserRole + 2;  ///< a "deformed by" row: its lattice's id

OutlinerEntry entryOf(const QTreeWidgetItem* item) {
  OutlinerEntry e;
  const QVariant kind = item->data(0, kKindRole);
  if (!kind.isValid()) return e;
  e.kind = static_cast<OutlinerEntry::Kind>(kind.toInt());
  switch (e.kind) {
    case OutlinerEntry::Kind::Object: e.object.value = item->data(0, kIdRole).toUInt(); break;
    case OutlinerEntry::Kind::Widget: e.widget.value = item->data(0, kIdRole).toUInt(); break;
    case OutlinerEntry::Kind::Binding: e.binding.value = item->data(0, kIdRole).toUInt(); break;
  }
  return e;
}

QString qs(const std::string& s) { return QString::fromStdString(s); }

// The text of a row (name, type) from the model: one home for rebuild and sync.
QString latticeType(const widgets::WidgetModel& m, widgets::WidgetId lattice) {
  const Eigen::Vector3i n = m.counts(lattice);
  return Outliner::tr("lattice %1x%2x%3").arg(n.x()).arg(n.y()).arg(n.z());
}

QString widgetType(const widgets::WidgetModel& m, widgets::WidgetId id) {
  switch (m.type(id)) {
    case widgets::WidgetType::Lattice: return latticeType(m, id);
    case widgets::WidgetType::Cell:
      return Outliner::tr("%1 cell").arg(qs(std::string(cellKindName(m.cellSpec(id).kind))));
    case widgets::WidgetType::Affine: {
      const QString kind = qs(std::string(affineKindName(m.affineKind(id))));
      return m.attachedCell(id) ? kind : Outliner::tr("free %1").arg(kind);
    }
  }
  return {};
}

QString bindingText(const widgets::WidgetModel& m, widgets::BindingId id) {
  const widgets::Binding& b = m.binding(id);
  return qs(m.name(b.from) + (b.oneWay ? " -> " : " <-> ") + m.name(b.to));
}

bool setText(QTreeWidgetItem* item, const QString& name, const QString& type) {
  if (item->text(0) == name && item->text(1) == type) return false;
  item->setText(0, name);
  item->setText(1, type);
  return true;
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
  auto widgetRow = [&](QTreeWidgetItem* parent, widgets::WidgetId id) {
    return makeItem(parent, qs(m.name(id)), widgetType(m, id), OutlinerEntry::Kind::Widget, id.value);
  };
  auto* objects = new QTreeWidgetItem(this, {tr("Objects")});
  for (const auto& object : scene.objects()) {
    auto* item = makeItem(objects, qs(object.name), tr("object"), OutlinerEntry::Kind::Object, object.id.value);
    for (widgets::WidgetId lattice : scene.latticesDeforming(object.id))
      (new QTreeWidgetItem(item, {qs(m.name(lattice)), tr("deformed by")}))->setData(0, kDeformedByRole, lattice.value);
  }
  auto* tree = new QTreeWidgetItem(this, {tr("Widgets")});
  std::function<void(QTreeWidgetItem*, widgets::WidgetId)> addLattice = [&](QTreeWidgetItem* parent,
                                                                             widgets::WidgetId lattice) {
    auto* item = widgetRow(parent, lattice);
    for (widgets::WidgetId cell : m.cellsOf(lattice)) {
      auto* cellItem = widgetRow(item, cell);
      for (widgets::WidgetId affine : m.affinesOf(cell)) widgetRow(cellItem, affine);
      for (widgets::WidgetId child : m.children(lattice))
        if (m.parentCell(child) == cell) addLattice(cellItem, child);
    }
  };
  for (widgets::WidgetId root : m.roots()) addLattice(tree, root);
  for (widgets::WidgetId affine : m.widgets(widgets::WidgetType::Affine))
    if (!m.attachedCell(affine)) widgetRow(tree, affine);
  auto* bindings = new QTreeWidgetItem(this, {tr("Bindings")});
  for (widgets::BindingId id : m.bindings())
    makeItem(bindings, bindingText(m, id), qs(std::string(bindingKindName(m.binding(id).kind))),
             OutlinerEntry::Kind::Binding, id.value);
  for (auto* top : {objects, tree, bindings}) top->setFlags(top->flags() & ~Qt::ItemIsSelectable & ~Qt::ItemIsDragEnabled);
  expandAll();
  programmatic_ = false;
  select(keep);
  mark_ = scenes::markOf(scene);
  ++stats_.rebuilds;
  for (QTreeWidgetItemIterator it(this); *it; ++it) ++stats_.rowsBuilt;
}

void Outliner::sync(const scenes::Scene& scene) {
  const scenes::SceneChanges changes = scenes::changesSince(scene, mark_);
  if (changes.widgetsReplaced || changes.structure || changes.widgets.structure) {
    rebuild(scene);
    return;
  }
  mark_ = scenes::markOf(scene);
  // What a row shows: names and kinds of widgets (widgets), counts of lattices (frames: new
  // counts), the direction of bindings (bindings).
  std::set<widgets::WidgetId> touched(changes.widgets.widgets.begin(), changes.widgets.widgets.end());
  touched.insert(changes.widgets.frames.begin(), changes.widgets.frames.end());
  const std::set<widgets::BindingId> bindings(changes.widgets.bindings.begin(), changes.widgets.bindings.end());
  if (touched.empty() && bindings.empty()) return;
  const auto& m = scene.widgets;
  for (QTreeWidgetItemIterator it(this); *it; ++it) {
    QTreeWidgetItem* item = *it;
    bool updated = false;
    if (const QVariant lattice = item->data(0, kDeformedByRole); lattice.isValid()) {
      const widgets::WidgetId id{lattice.toUInt()};
      if (touched.count(id) != 0) updated = setText(item, qs(m.name(id)), tr("deformed by"));
    } else if (item->data(0, kKindRole).isValid()) {
      const OutlinerEntry e = entryOf(item);
      if (e.kind == OutlinerEntry::Kind::Widget && touched.count(e.widget) != 0) {
        updated = setText(item, qs(m.name(e.widget)), widgetType(m, e.widget));
      } else if (e.kind == OutlinerEntry::Kind::Binding) {
        const widgets::Binding& b = m.binding(e.binding);
        if (bindings.count(e.binding) != 0 || touched.count(b.from) != 0 || touched.count(b.to) != 0)
          updated = setText(item, bindingText(m, e.binding), item->text(1));
      }
    }
    if (updated) ++stats_.rowsUpdated;
  }
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
