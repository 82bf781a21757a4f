#include "ffdkit/geometry/polyhedron/ring_targets.h"

#include <random>
#include <stdexcept>

#include <Eigen/QR>
#include <gtest/gtest.h>

namespace ffdkit::geometry::polyhedron {
namespace {

Eigen::MatrixXd cyclicMatrix(int n) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    a(i, i) = 1.0;
    a(i, (i + n - 1) % n) = 1.0;
  }
  return a;
}

TEST(RingTargets, EqualsTheMinimumNormSolutionForEveryRingSize) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int n = 2; n <= 12; ++n) {  // N = 1 is no ring (its equation reads 2 G_0 = R_0)
    Eigen::MatrixX3d r(n, 3);
    for (int i = 0; i < n; ++i) r.row(i) << uniform(random), uniform(random), uniform(random);
    const Eigen::MatrixX3d expected = cyclicMatrix(n).completeOrthogonalDecomposition().pseudoInverse() * r;
    EXPECT_LE((ringTargets(r) - expected).norm(), 1e-12) << "N = " << n;
  }
}

TEST(RingTargets, SolvesOddRingsExactlyAndEvenRingsUpToTheAlternatingDefect) {
  Eigen::MatrixX3d r5 = Eigen::MatrixX3d::Random(5, 3);
  EXPECT_LE((cyclicMatrix(5) * ringTargets(r5) - r5).norm(), 1e-12);
  Eigen::MatrixX3d r6 = Eigen::MatrixX3d::Random(6, 3);
  const Eigen::MatrixX3d g = ringTargets(r6);
  Eigen::RowVector3d alternating = Eigen::RowVector3d::Zero();
  for (int i = 0; i < 6; ++i) alternating += ((i % 2) ? -1.0 : 1.0) * g.row(i);
  EXPECT_LE(alternating.norm(), 1e-12);  // the thesis symmetry constraint (Kuriyama 1996, sec. 4.3.2)
}

TEST(RingTargets, IsTranslationInvariant) {
  for (int n : {5, 6}) {
    const Eigen::MatrixX3d r = Eigen::MatrixX3d::Random(n, 3);
    const Eigen::RowVector3d shift(1.0, -2.0, 3.0);
    const Eigen::MatrixX3d shifted = r.rowwise() + 2.0 * shift;  // G_i + G_{i-1} = R_i: targets move by shift
    EXPECT_LE((ringTargets(shifted) - (ringTargets(r).rowwise() + shift)).norm(), 1e-12);
  }
}

TEST(RingTargets, RejectsEmptyRing) { EXPECT_THROW(ringTargets(Eigen::MatrixX3d(0, 3)), std::invalid_argument); }

}  // namespace
}  // namespace ffdkit::geometry::polyhedron
