#pragma once

#include <array>
#include <optional>
#include <string_view>

#include "ffdkit/ffd/axis_basis.h"
#include "ffdkit/ffd/outside_policy.h"
#include "ffdkit/ffd/rest_shape.h"

namespace ffdkit::widgets {

/// How often lattices other than the dragged one are re-embedded (Kuriyama 1996, sec. 6.2.3,
/// sec. 6.3.2).
enum class ReembedKind { Immediate, EveryN, OnRelease };
/// How often a lattice other than the dragged one re-embeds (a widget file's "reembed").
struct ReembedPolicy {
  ReembedKind kind = ReembedKind::Immediate;  ///< the rule
  int everyN = 1;  ///< EveryN only: >= 1
  friend bool operator==(const ReembedPolicy&, const ReembedPolicy&) = default;  ///< equal when kind and everyN are
};

std::string_view reembedKindName(ReembedKind kind);  // "immediate", "every-n", "on-release"
std::optional<ReembedKind> parseReembedKind(std::string_view name);

/// Per-lattice FFD settings that a widget file carries (Kuriyama 1996, secs. 6.3.2, 6.2.3, 6.3.3),
/// in the FFD engine's own types: the model stores them and WidgetModel::ffdLattice hands them to
/// ffd::Lattice.
struct LatticeSettings {
  /// Per axis (u, v, w). Bernstein by default (Sederberg & Parry FFD): valid for any count.
  std::array<ffd::AxisBasis, 3> basis{ffd::AxisBasis::bernstein(), ffd::AxisBasis::bernstein(),
                                      ffd::AxisBasis::bernstein()};
  ffd::OutsidePolicy outside{};  ///< what happens to object points outside the lattice
  ReembedPolicy reembed{};  ///< when the lattice re-embeds while another is dragged
  /// Set for a cylindrical (EFFD) rest lattice (Kuriyama 1996, Fig. 6-11): the analytic cylinder
  /// its rest points sample, which gives Newton embedding its initial guess (radius, angle,
  /// height). Without it, points near the axis can converge to the mirrored angle.
  std::optional<ffd::CylinderRestShape> cylinder;
};

/// Whether two settings are equal: bases (kind, degree, knots), outside policy, re-embed policy
/// and cylinder, compared exactly.
bool sameLatticeSettings(const LatticeSettings& a, const LatticeSettings& b);

}  // namespace ffdkit::widgets
