#pragma once

#include <vector>

#include <QWidget>

#include "outliner.h"

class QFormLayout;

namespace ffdkit::app {

class InteractionController;

/// Properties of the selection, generated from the model: an affine widget (kind, variation,
/// placement, glyph or part), a binding (one-way direction, mask as T/R/S toggle buttons,
/// conversion rule gain and clamp range), a lattice (counts, basis per axis, outside policy), a
/// cell, an object (its look: shaded or zebra for a surface, tube or line and a comb for a
/// curve). Every edit goes through the controller (one undoable command); an edit the
/// model rejects is reported with `error` and its control shows the model's value again.
/// Controls carry object names for tests ("kind", "oneWay", "countU", "basisV", ...).
class PropertyPanel : public QWidget {
  Q_OBJECT

 public:
  PropertyPanel(InteractionController& controller, const scenes::Scene& scene, QWidget* parent = nullptr);
  /// Shows the properties of `selection` (the first entry; several entries just list them).
  void showSelection(const std::vector<OutlinerEntry>& selection);

 signals:
  void error(const QString& message);

 private:
  void clearRows();
  void showAffine(widgets::WidgetId id);
  void showBinding(widgets::BindingId id);
  void showLattice(widgets::WidgetId id);
  void showCell(widgets::WidgetId id);
  void showObject(const std::string& name);
  /// Runs an edit; on an error reports it with `error` and returns false (the caller then puts
  /// its control back to the model's value).
  template <class F>
  bool guarded(F f);

  InteractionController& controller_;
  const scenes::Scene& scene_;
  QWidget* content_ = nullptr;  ///< replaced on every showSelection (deleted later: a row may be emitting)
  QFormLayout* form_ = nullptr;
};

}  // namespace ffdkit::app
