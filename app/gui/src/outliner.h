#pragma once

#include <optional>
#include <string>
#include <vector>

#include <QTreeWidget>

#include "ffdkit/scenes/scene.h"

namespace ffdkit::app {

/// One row of the outliner: an object, a widget (lattice, cell, affine) or a binding.
struct OutlinerEntry {
  enum class Kind { Object, Widget, Binding } kind = Kind::Object;
  std::string object;
  widgets::WidgetId widget;
  widgets::BindingId binding;
};

/// The outliner: objects (with the lattices deforming them), the widget tree (root lattices in
/// sibling order, their cells, the cells' affine widgets and child lattices) and the bindings.
/// Lattices are reordered among their siblings by drag and drop (siblingMoveRequested).
class Outliner : public QTreeWidget {
  Q_OBJECT

 public:
  explicit Outliner(QWidget* parent = nullptr);

  /// Rebuilds every row from `scene`, keeping the selection where the rows still exist.
  void rebuild(const scenes::Scene& scene);
  /// Selects these rows without emitting selectionEdited.
  void select(const std::vector<OutlinerEntry>& entries);
  std::vector<OutlinerEntry> selection() const;
  /// The row of a widget / object / binding, or nullptr.
  QTreeWidgetItem* itemFor(const OutlinerEntry& entry) const;

 signals:
  /// The user changed the selection.
  void selectionEdited();
  /// The user dropped `lattice` onto a sibling at `position`.
  void siblingMoveRequested(widgets::WidgetId lattice, int position);

 protected:
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dragMoveEvent(QDragMoveEvent* event) override;
  void dropEvent(QDropEvent* event) override;

 private:
  bool programmatic_ = false;
};

}  // namespace ffdkit::app
