#pragma once

#include <optional>
#include <string_view>

#include "ffdkit/widgets/affine_mask.h"
#include "ffdkit/widgets/widget_id.h"

namespace ffdkit::widgets {

/// The four binding kinds of Kuriyama 1996, sec. 6.2.2 (束縛関係), decided by the kinds of
/// the two widgets bound (sec. 6.4):
/// - Attachment: cell -> affine widget; the widget drives the cell's points and follows the
///   cell's masked motion.
/// - Variation: affine -> affine; the variation change is carried through a ConversionRule.
/// - CellMotion: cell -> cell; the masked world motion of one is given to the other.
/// - Hierarchy: cell -> lattice widget of another lattice; the lattice becomes that cell's
///   child and its frame follows the cell (mask default {T, R, S}).
enum class BindingKind { Attachment, Variation, CellMotion, Hierarchy };
std::string_view bindingKindName(BindingKind kind);  // "attachment", "variation", "cell-motion", "hierarchy"
std::optional<BindingKind> parseBindingKind(std::string_view name);

/// Closed range of a variation (distance, angle in rad, or log scale factor).
struct VariationRange {
  double min = 0.0;  ///< lower end
  double max = 0.0;  ///< upper end (>= min)
  friend bool operator==(const VariationRange&, const VariationRange&) = default;  ///< equal when both ends are
};

/// Conversion rule of an affine <-> affine binding (変換則, sec. 6.2.2):
///   delta_to = gain * delta_from   (and delta_from = delta_to / gain when driven backwards).
/// Variations are additive scalars (distance, angle in rad, log scale), so converting distance
/// to angle to log-scale is a gain with units: rad per unit, unit per rad, ...
/// `clamp` bounds the accumulated variation of the `to` widget (a vise jaw stops); it applies
/// when the binding drives its `to` end.
struct ConversionRule {
  /// A rule with this gain and, optionally, a clamp range.
  ConversionRule(double gainValue = 1.0, std::optional<VariationRange> clampRange = std::nullopt)
      : gain(gainValue), clamp(clampRange) {}

  double gain = 1.0;  ///< != 0, finite
  std::optional<VariationRange> clamp;  ///< bounds of the `to` widget's accumulated variation; none: unbounded

  /// A screw: `distancePerTurn` of translation per full turn (2 pi rad) of a rotate widget,
  /// for a binding from the rotate widget to the translate widget (Kuriyama 1996, Fig. 6-10).
  static ConversionRule screw(double distancePerTurn);
  friend bool operator==(const ConversionRule&, const ConversionRule&) = default;  ///< equal when gain and clamp are
};

/// One binding. `from` and `to` follow the kind's order above. Two-way unless `oneWay`, in
/// which case only `from` drives `to` (for Attachment: the widget only follows its cell).
struct Binding {
  BindingId id;  ///< the binding's id
  BindingKind kind = BindingKind::Variation;  ///< decided by the kinds of the two widgets
  WidgetId from;  ///< the driving end
  WidgetId to;  ///< the driven end
  AffineMask mask = AffineMask::tr();  ///< Attachment, CellMotion, Hierarchy
  ConversionRule rule;                 ///< Variation only
  bool oneWay = false;  ///< only `from` drives `to`
  friend bool operator==(const Binding&, const Binding&) = default;  ///< equal when every field is
};

/// Options of WidgetModel::bind. The kind is decided by the widgets; `mask` defaults by kind:
/// Attachment by cell kind (defaultAttachmentMask), CellMotion {T, R}, Hierarchy {T, R, S}.
struct BindingOptions {
  ConversionRule rule;  ///< Variation bindings: the conversion rule
  std::optional<AffineMask> mask;  ///< none: the default mask of the kind
  bool oneWay = false;  ///< only the first widget drives the second
};

}  // namespace ffdkit::widgets
