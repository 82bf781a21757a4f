#pragma once

#include <cstdint>
#include <vector>

#include "ffdkit/widgets/widget_id.h"

namespace ffdkit::widgets {

/// What changed in a WidgetModel between two of its revisions (WidgetModel::changesSince), the
/// change set its consumers read instead of diffing the model (VTK's modified times, Blender's
/// recalc tags): the FFD pipeline re-embeds the lattices in `frames` and re-deforms those in
/// `controlPoints`; a view redraws the widgets listed; the outliner rebuilds on `structure`.
///
/// Every mutation of the model takes one new model revision and stamps each item it changed with
/// it (WidgetModel::controlRevision, frameRevision, widgetRevision, bindingRevision,
/// structureRevision). A consumer keeps the revision it last saw and asks for what is newer.
/// Revisions compare within one model instance only (WidgetModel::instance): a copy or a model
/// read from data is a new instance, which its consumers take in full.
struct WidgetChanges {
  std::uint64_t since = 0;     ///< the revision asked about (exclusive)
  std::uint64_t revision = 0;  ///< the model's revision now (inclusive)
  /// Widgets or bindings added or removed, a lattice re-parented (bound, unbound) or moved among
  /// its siblings, a cell's point set changed by new counts: whatever changes the trees' shape.
  bool structure = false;
  /// Lattices whose local control points changed (a drag, setControlPoints, an undo).
  std::vector<WidgetId> controlPoints;
  /// Lattices whose rest lattice in the world changed: frame, rest points, counts, bases, outside
  /// policy, or for a child lattice its parent cell or binding mask (what an embedding depends on).
  std::vector<WidgetId> frames;
  /// Widgets whose own data changed: name, placement, glyph, variation, kind, lattice settings.
  std::vector<WidgetId> widgets;
  /// Bindings whose mask, conversion rule or direction changed.
  std::vector<BindingId> bindings;

  /// True when nothing changed.
  bool empty() const {
    return !structure && controlPoints.empty() && frames.empty() && widgets.empty() && bindings.empty();
  }
};

}  // namespace ffdkit::widgets
