#include "ffdkit/widgets/lattice_settings.h"

namespace ffdkit::widgets {
namespace {

bool sameBasis(const ffd::AxisBasis& a, const ffd::AxisBasis& b) {
  return a.kind == b.kind && a.degree == b.degree && a.knots.size() == b.knots.size() && a.knots == b.knots;
}

}  // namespace

bool sameLatticeSettings(const LatticeSettings& a, const LatticeSettings& b) {
  for (std::size_t axis = 0; axis < 3; ++axis)
    if (!sameBasis(a.basis[axis], b.basis[axis])) return false;
  if (a.cylinder.has_value() != b.cylinder.has_value()) return false;
  if (a.cylinder && (a.cylinder->innerRadius != b.cylinder->innerRadius || a.cylinder->outerRadius != b.cylinder->outerRadius ||
                     a.cylinder->zMin != b.cylinder->zMin || a.cylinder->zMax != b.cylinder->zMax))
    return false;
  return a.outside == b.outside && a.reembed == b.reembed;
}

}  // namespace ffdkit::widgets
