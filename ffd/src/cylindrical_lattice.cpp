#include "ffdkit/ffd/cylindrical_lattice.h"

#include <cmath>
#include <numbers>
#include <string>

namespace ffdkit::ffd {

Lattice makeCylindricalLattice(const CylindricalLatticeOptions& options) {
  const auto& c = options.counts;
  if ((c.array() < 2).any()) {
    throw LatticeError("lattice needs >= 2 points per axis, got (" + std::to_string(c[0]) + ", " +
                       std::to_string(c[1]) + ", " + std::to_string(c[2]) + ")");
  }
  if (options.bases[1].kind != AxisBasis::Kind::PeriodicBSpline) {
    throw LatticeError("cylindrical lattice: the angular axis (v) needs a periodic B-spline basis");
  }
  if (options.bases[0].kind == AxisBasis::Kind::PeriodicBSpline ||
      options.bases[2].kind == AxisBasis::Kind::PeriodicBSpline) {
    throw LatticeError("cylindrical lattice: the radial (u) and height (w) axes cannot be periodic");
  }
  if (!(options.innerRadius >= 0.0) || !(options.outerRadius > options.innerRadius) ||
      !std::isfinite(options.outerRadius) || !(options.zMax > options.zMin) || !std::isfinite(options.zMin) ||
      !std::isfinite(options.zMax)) {
    throw LatticeError("cylindrical lattice needs 0 <= innerRadius < outerRadius and zMin < zMax, got radii [" +
                       std::to_string(options.innerRadius) + ", " + std::to_string(options.outerRadius) +
                       "], z [" + std::to_string(options.zMin) + ", " + std::to_string(options.zMax) + "]");
  }
  std::array<AxisBasis, 3> bases = options.bases;
  for (int a : {0, 2}) {
    if (bases[a].kind == AxisBasis::Kind::BSpline && bases[a].knots.size() == 0 && bases[a].degree > c[a] - 1) {
      bases[a].degree = c[a] - 1;
    }
  }
  const AxisSpline radial(bases[0], c[0], "cylindrical lattice radial axis u");
  const AxisSpline angular(bases[1], c[1], "cylindrical lattice angular axis v");
  const AxisSpline height(bases[2], c[2], "cylindrical lattice height axis w");
  auto normalized = [](const AxisSpline& axis, int i) {
    return (axis.greville()[i] - axis.domainMin()) / (axis.domainMax() - axis.domainMin());
  };
  Eigen::MatrixX3d rest(c.prod(), 3);
  for (int k = 0; k < c[2]; ++k) {
    const double z = options.zMin + (options.zMax - options.zMin) * normalized(height, k);
    for (int j = 0; j < c[1]; ++j) {
      const double t = 2.0 * std::numbers::pi * angular.greville()[j];
      for (int i = 0; i < c[0]; ++i) {
        const double r = options.innerRadius + (options.outerRadius - options.innerRadius) * normalized(radial, i);
        // The i = 0 ring of a solid cylinder sits exactly on the axis: r = 0, no trigonometric noise.
        rest.row(i + c[0] * (j + c[1] * k)) << (r == 0.0 ? 0.0 : r * std::cos(t)), (r == 0.0 ? 0.0 : r * std::sin(t)), z;
      }
    }
  }
  Lattice lattice(c, bases, rest, options.frame);
  lattice.setOutsidePolicy(options.outsidePolicy);
  lattice.setCylinderRestShape(CylinderRestShape{options.innerRadius, options.outerRadius, options.zMin, options.zMax});
  return lattice;
}

}  // namespace ffdkit::ffd
