// ffdkit::ffd from an installed package: a trilinear box whose top face rises by 0.5 scales z
// by 1.5 (Sederberg & Parry 1986, eq. (1) with degree 1 per axis), checked by hand values.
#include <cmath>

#include "../consumer_check.h"
#include "ffdkit/ffd/deformer.h"
#include "ffdkit/ffd/embedding.h"
#include "ffdkit/ffd/lattice.h"

using namespace ffdkit;

int main() {
  ffd::BoxLatticeOptions options;
  options.counts = Eigen::Vector3i(2, 2, 2);
  options.bases = {ffd::AxisBasis::bernstein(), ffd::AxisBasis::bernstein(), ffd::AxisBasis::bernstein()};
  ffd::Lattice lattice = ffd::makeBoxLattice(options);
  Eigen::MatrixX3d control = lattice.controlPoints();
  for (Eigen::Index p = 4; p < 8; ++p) control(p, 2) += 0.5;  // the four points with z = 1
  lattice.setControlPoints(control);
  Eigen::MatrixX3d points(2, 3);
  points << 0.2, 0.3, 0.4,  //
      0.9, 0.1, 1.0;
  ffd::Deformer deformer(ffd::embed(lattice, points));
  const Eigen::MatrixX3d& out = deformer.deform(lattice, points);
  consumer::check(std::abs(out(0, 2) - 0.6) < 1e-14 && std::abs(out(1, 2) - 1.5) < 1e-14, "z scales by 1.5");
  consumer::check(std::abs(out(0, 0) - 0.2) < 1e-14 && std::abs(out(1, 1) - 0.1) < 1e-14, "x and y stay");
  return consumer::exitCode();
}
