// Names of the small enums and ids used in files and the UI.
#include <charconv>
#include <cmath>
#include <numbers>

#include "ffdkit/widgets/affine_mask.h"
#include "ffdkit/widgets/binding.h"
#include "ffdkit/widgets/lattice_settings.h"
#include "ffdkit/widgets/widget_error.h"
#include "ffdkit/widgets/widget_id.h"

namespace ffdkit::widgets {
namespace {

template <class Id>
std::optional<Id> parseId(std::string_view text, char prefix) {
  if (text.size() < 2 || text.front() != prefix) return std::nullopt;
  std::uint32_t value = 0;
  const char* first = text.data() + 1;
  const char* last = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(first, last, value);
  if (ec != std::errc() || ptr != last || value == Id::kInvalid) return std::nullopt;
  if (text.size() > 2 && text[1] == '0') return std::nullopt;  // one spelling per id
  return Id{value};
}

template <class Enum, std::size_t N>
std::optional<Enum> parseByName(std::string_view name, const Enum (&all)[N],
                                std::string_view (*nameOf)(Enum)) {
  for (Enum e : all) {
    if (nameOf(e) == name) return e;
  }
  return std::nullopt;
}

}  // namespace

namespace {
std::string prefixed(char prefix, std::uint32_t value) {
  std::string s(1, prefix);
  s += std::to_string(value);  // appended, not operator+: GCC 12 -Wrestrict false positive
  return s;
}
}  // namespace

std::string toString(WidgetId id) { return id.valid() ? prefixed('w', id.value) : "none"; }
std::string toString(BindingId id) { return id.valid() ? prefixed('b', id.value) : "none"; }
std::optional<WidgetId> parseWidgetId(std::string_view text) { return parseId<WidgetId>(text, 'w'); }
std::optional<BindingId> parseBindingId(std::string_view text) { return parseId<BindingId>(text, 'b'); }

std::string_view widgetTypeName(WidgetType type) {
  switch (type) {
    case WidgetType::Lattice: return "lattice";
    case WidgetType::Cell: return "cell";
    case WidgetType::Affine: return "affine";
  }
  return "unknown";
}

WidgetError::WidgetError(WidgetErrorCode code, const std::string& message, std::string where)
    : std::runtime_error(where.empty() ? message : where + ": " + message),
      code_(code),
      where_(std::move(where)),
      message_(message) {}

std::string maskString(AffineMask mask) {
  std::string s;
  if (mask.translate) s += 'T';
  if (mask.rotate) s += 'R';
  if (mask.scale) s += 'S';
  return s;
}

std::optional<AffineMask> parseMask(std::string_view text) {
  AffineMask m = AffineMask::none();
  for (char c : text) {
    bool* slot = c == 'T' ? &m.translate : c == 'R' ? &m.rotate : c == 'S' ? &m.scale : nullptr;
    if (slot == nullptr || *slot) return std::nullopt;
    *slot = true;
  }
  return m;
}

std::string_view bindingKindName(BindingKind kind) {
  switch (kind) {
    case BindingKind::Attachment: return "attachment";
    case BindingKind::Variation: return "variation";
    case BindingKind::CellMotion: return "cell-motion";
    case BindingKind::Hierarchy: return "hierarchy";
  }
  return "unknown";
}
std::optional<BindingKind> parseBindingKind(std::string_view name) {
  static constexpr BindingKind all[] = {BindingKind::Attachment, BindingKind::Variation,
                                        BindingKind::CellMotion, BindingKind::Hierarchy};
  return parseByName(name, all, bindingKindName);
}

ConversionRule ConversionRule::screw(double distancePerTurn) {
  return ConversionRule{distancePerTurn / (2.0 * std::numbers::pi), std::nullopt};
}

std::string_view reembedKindName(ReembedKind kind) {
  switch (kind) {
    case ReembedKind::Immediate: return "immediate";
    case ReembedKind::EveryN: return "every-n";
    case ReembedKind::OnRelease: return "on-release";
  }
  return "unknown";
}
std::optional<ReembedKind> parseReembedKind(std::string_view name) {
  static constexpr ReembedKind all[] = {ReembedKind::Immediate, ReembedKind::EveryN,
                                        ReembedKind::OnRelease};
  return parseByName(name, all, reembedKindName);
}

}  // namespace ffdkit::widgets
