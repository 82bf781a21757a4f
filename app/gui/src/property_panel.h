#pragma once

#include <exception>
#include <functional>
#include <string>
#include <vector>

#include <QWidget>

#include "ffdkit/scenes/scene_changes.h"
#include "outliner.h"

class QFormLayout;
class QLabel;

namespace ffdkit::app {

class EditController;
class InteractionController;

/// Properties of the selection, generated from the model: an affine widget (kind, variation,
/// placement, glyph or part), a binding (one-way direction, mask as T/R/S toggle buttons,
/// conversion rule gain and clamp range), a lattice (counts, basis per axis, outside policy), a
/// cell, an object (its look: shaded or zebra for a surface, tube or line and a comb for a
/// curve). Every edit goes through the controller (one undoable command); an edit the
/// model rejects is reported with `error` and its control shows the model's value again.
/// Controls carry object names for tests ("kind", "oneWay", "countU", "basisV", ...).
/// Change-driven: showing the same selection again after an edit, a drag or an undo rebuilds
/// nothing while the rows it needs are the same (layoutOf()): it reads the scene's change set and,
/// when something changed, puts the model's present value into each control whose value differs
/// (signals blocked). Hover and selection of the same item change nothing.
/// In a lattice's edit mode (`edit` given and editing) the panel starts with the edited points:
/// how many are selected and, for one or more, their weight (showEditedPoints()).
class PropertyPanel : public QWidget {
  Q_OBJECT

 public:
  /// `edit` (may be null: no edit-mode rows) must outlive the panel, as `controller` and `scene`.
  PropertyPanel(InteractionController& controller, const scenes::Scene& scene, const EditController* edit = nullptr,
                QWidget* parent = nullptr);
  /// Shows the properties of `selection` (the first entry; several entries just list them),
  /// after the edit mode's points when editing: builds the rows for another selection or layout,
  /// else updates the changed fields in place.
  void showSelection(const std::vector<OutlinerEntry>& selection);

  /// What the panel did, for tests: row sets built, controls whose shown value a sync changed.
  struct Stats {
    int rebuilds = 0;
    int fieldsUpdated = 0;
  };
  const Stats& stats() const { return stats_; }

 signals:
  void error(const QString& message);

 private:
  void clearRows();
  /// What decides the rows of `selection` (which item, its type, kind, the choices its combos
  /// offer): the same layout takes in-place updates, another one a rebuild.
  std::string layoutOf(const std::vector<OutlinerEntry>& selection) const;
  /// The edit mode's part of the layout: the edited lattice, its counts and the selected points
  /// ("" outside the edit mode).
  std::string editLayout() const;
  /// The edit mode's rows: the selected points' count and, when there are any, their weight.
  void showEditedPoints();
  void showAffine(widgets::WidgetId id);
  void showBinding(widgets::BindingId id);
  void showLattice(widgets::WidgetId id);
  /// The weight of control points `points` of lattice `id` (the picked point, or the edit mode's
  /// selected points): a text field named `name` (its message: name + "Message") showing their
  /// weight, blank when they differ. Enter sets every one of them to the typed weight (one
  /// command); text that is no number, or a weight not finite and > 0, is refused with the reason
  /// under the field, the model untouched.
  void addWeightRow(widgets::WidgetId id, const std::vector<Eigen::Index>& points, const QString& name);
  void showCell(widgets::WidgetId id);
  void showObject(const std::string& name);
  /// A row "title: text()" whose text follows the model (a field).
  QLabel* addLabel(const QString& title, std::function<QString()> text);
  /// Runs an edit; on an error reports it with `error` and returns false (the caller then puts
  /// its control back to the model's value).
  template <class F>
  bool guarded(F f);

  InteractionController& controller_;
  const scenes::Scene& scene_;
  const EditController* edit_ = nullptr;
  QWidget* content_ = nullptr;  ///< replaced on a rebuild (deleted later: a row may be emitting)
  QFormLayout* form_ = nullptr;
  /// The controls of the rows shown: each puts the model's present value into its control and
  /// says whether the shown value changed.
  std::vector<std::function<bool()>> fields_;
  std::vector<OutlinerEntry> shown_;
  std::string layout_;      ///< layoutOf(shown_) when built; empty: nothing built yet
  scenes::SceneMark mark_;  ///< the scene as the fields show it
  Stats stats_;
};

template <class F>
bool PropertyPanel::guarded(F f) {
  try {
    f();
    return true;
  } catch (const std::exception& e) {
    emit error(QString::fromStdString(e.what()));
    return false;
  }
}

}  // namespace ffdkit::app
