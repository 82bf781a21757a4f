#pragma once

#include <optional>
#include <string_view>

namespace ffdkit::widgets {

/// The three affine widget kinds of Kuriyama 1996, sec. 6.2.1: each carries one scalar variation
/// (distance, angle in radians, or log of the scale factor).
enum class AffineKind { Translate, Rotate, Scale };

/// Stable lower-case name used in files and the UI ("translate", "rotate", "scale").
std::string_view affineKindName(AffineKind kind);

/// Inverse of affineKindName; std::nullopt for an unknown name.
std::optional<AffineKind> parseAffineKind(std::string_view name);

}  // namespace ffdkit::widgets
