#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace ffdkit::widgets {

/// Which affine components (translation, rotation, scale) a binding carries: the 拘束条件 of
/// Kuriyama 1996, sec. 6.2.2. For an attachment it says which components of the cell's motion the
/// affine widget follows; for a cell <-> cell binding which components are copied.
struct AffineMask {
  bool translate = true;  ///< the translation part passes
  bool rotate = true;  ///< the rotation part passes
  bool scale = false;  ///< the scale part passes

  /// Nothing passes.
  static constexpr AffineMask none() { return {false, false, false}; }
  /// Translation only {T}.
  static constexpr AffineMask t() { return {true, false, false}; }
  /// Translation and rotation {T, R}.
  static constexpr AffineMask tr() { return {true, true, false}; }
  /// Translation, rotation and scale {T, R, S}.
  static constexpr AffineMask trs() { return {true, true, true}; }
  friend constexpr bool operator==(const AffineMask&, const AffineMask&) = default;  ///< equal when every part is
};

/// "TRS", "TR", "T", "RS", ... in that letter order; "" for none.
std::string maskString(AffineMask mask);
/// Inverse of maskString (letters T, R, S each at most once, in any order); nullopt otherwise.
std::optional<AffineMask> parseMask(std::string_view text);

}  // namespace ffdkit::widgets
