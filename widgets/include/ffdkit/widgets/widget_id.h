#pragma once

#include <compare>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

namespace ffdkit::widgets {

/// Stable handle of a widget (lattice, cell or affine widget) inside one WidgetModel.
/// Ids are never reused within a model; files write them as "w<N>".
struct WidgetId {
  static constexpr std::uint32_t kInvalid = std::numeric_limits<std::uint32_t>::max();  ///< the value of an invalid id
  std::uint32_t value = kInvalid;  ///< the widget's number in its model

  /// True unless default-constructed.
  constexpr bool valid() const { return value != kInvalid; }
  friend constexpr auto operator<=>(const WidgetId&, const WidgetId&) = default;  ///< ordered by value
};

/// Stable handle of a binding inside one WidgetModel; files write it as "b<N>".
struct BindingId {
  static constexpr std::uint32_t kInvalid = std::numeric_limits<std::uint32_t>::max();  ///< the value of an invalid id
  std::uint32_t value = kInvalid;  ///< the binding's number in its model

  /// True unless default-constructed.
  constexpr bool valid() const { return value != kInvalid; }
  friend constexpr auto operator<=>(const BindingId&, const BindingId&) = default;  ///< ordered by value
};

/// "w12" / "b3"; "none" for an invalid id.
std::string toString(WidgetId id);
std::string toString(BindingId id);
/// Inverse of toString; std::nullopt unless the text is "w<digits>" / "b<digits>".
std::optional<WidgetId> parseWidgetId(std::string_view text);
std::optional<BindingId> parseBindingId(std::string_view text);

/// The three widget families of Kuriyama 1996, ch. 6 (secs. 6.2.1, 6.2.3).
enum class WidgetType { Lattice, Cell, Affine };
std::string_view widgetTypeName(WidgetType type);

}  // namespace ffdkit::widgets
