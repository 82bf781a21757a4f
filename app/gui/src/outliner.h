#pragma once

#include <optional>
#include <string>
#include <vector>

#include <QTreeWidget>

#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_changes.h"

namespace ffdkit::app {

/// One row of the outliner: an object, a widget (lattice, cell, affine) or a binding.
struct OutlinerEntry {
  enum class Kind { Object, Widget, Binding } kind = Kind::Object;
  scenes::ObjectId object;  ///< the object's id (a rename keeps the row and its selection)
  widgets::WidgetId widget;
  widgets::BindingId binding;
};

/// The outliner: objects (with the lattices deforming them), the widget tree (root lattices in
/// sibling order, their cells, the cells' affine widgets and child lattices) and the bindings.
/// Lattices are reordered among their siblings by drag and drop (siblingMoveRequested).
/// Change-driven: sync() reads the scene's change set (scenes::changesSince) and rebuilds the rows
/// only for a new structure; a renamed widget or a changed binding rewrites the rows showing it.
class Outliner : public QTreeWidget {
  Q_OBJECT

 public:
  explicit Outliner(QWidget* parent = nullptr);

  /// Rebuilds every row from `scene`, keeping the selection where the rows still exist.
  void rebuild(const scenes::Scene& scene);
  /// Brings the rows up to date with what changed in `scene` since the last rebuild or sync:
  /// another widget model, objects or attachments added, removed or renamed, or widgets or
  /// bindings added, removed or moved rebuild every row; a widget's own change (name, kind,
  /// counts) or a binding's (direction) rewrites only the rows that show it (its own, the
  /// "deformed by" rows of a lattice, the bindings naming it). Nothing changed: nothing done.
  void sync(const scenes::Scene& scene);

  /// What the outliner did, for tests: rows built by rebuilds, rows whose text a sync rewrote.
  struct Stats {
    int rebuilds = 0;
    int rowsBuilt = 0;
    int rowsUpdated = 0;
  };
  const Stats& stats() const { return stats_; }
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
  scenes::SceneMark mark_;  ///< the scene as the rows show it
  Stats stats_;
};

}  // namespace ffdkit::app
