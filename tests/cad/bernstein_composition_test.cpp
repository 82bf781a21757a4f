#include "ffdkit/cad/bernstein_composition.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "cad_test_support.h"
#include "ffdkit/cad/cad_error.h"
#include "ffdkit/ffd/box_lattice_options.h"

namespace ffdkit::cad {
namespace {

using test::deformedLatticeAround;
using test::ffdOf;

/// A bicubic patch with poles jittered around a wavy sheet in [0.1, 0.9]^2 x [0.3, 0.7].
BezierPatch wavyPatch(int p, int q, bool rational, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  std::uniform_real_distribution<double> weight(0.5, 2.0);
  BezierPatch patch;
  patch.degreeU = p;
  patch.degreeV = q;
  patch.poles.resize(patch.poleCount(), 3);
  if (rational) patch.weights.resize(patch.poleCount());
  for (int b = 0; b <= q; ++b)
    for (int a = 0; a <= p; ++a) {
      const double s = p ? double(a) / p : 0.5, t = q ? double(b) / q : 0.5;
      const Eigen::Index row = a + (p + 1) * b;
      patch.poles.row(row) << 0.1 + 0.8 * s + jitter(rng), 0.1 + 0.8 * t + jitter(rng), 0.5 + 0.15 * std::sin(4 * s) + jitter(rng);
      if (rational) patch.weights[row] = weight(rng);
    }
  return patch;
}

const Eigen::AlignedBox3d kUnitBox(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));

double maxDifference(const BezierPatch& composed, const BezierPatch& original, const ffd::Lattice& lattice) {
  double worst = 0.0;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j) {
      const double s = i / 10.0, t = original.degreeV ? j / 10.0 : 0.0;
      worst = std::max(worst, (composed.evaluate(s, t) - ffdOf(lattice, original.evaluate(s, t))).norm());
    }
  return worst;
}

TEST(BernsteinComposition, PolynomialPatchEqualsTheFfdOfItsPoints) {
  const ffd::Lattice lattice = deformedLatticeAround(kUnitBox, {3, 4, 2}, 0.2);
  const BernsteinVolume volume = BernsteinVolume::fromLattice(lattice);
  const BezierPatch patch = wavyPatch(3, 2, false, 7);
  const BezierPatch composed = composeBezierPatch(volume, patch);
  EXPECT_EQ(composed.degreeU, (2 + 3 + 1) * 3);
  EXPECT_EQ(composed.degreeV, (2 + 3 + 1) * 2);
  EXPECT_EQ(composed.weights.size(), 0);  // polynomial in, polynomial out
  EXPECT_LT(maxDifference(composed, patch, lattice), 1e-13);
}

TEST(BernsteinComposition, RationalPatchEqualsTheFfdOfItsPoints) {
  const ffd::Lattice lattice = deformedLatticeAround(kUnitBox, {3, 3, 3}, 0.25);
  const BezierPatch patch = wavyPatch(2, 2, true, 11);
  const BezierPatch composed = composeBezierPatch(BernsteinVolume::fromLattice(lattice), patch);
  EXPECT_EQ(composed.degreeU, 12);
  ASSERT_EQ(composed.weights.size(), composed.poleCount());
  EXPECT_GT(composed.weights.minCoeff(), 0.0);
  EXPECT_LT(maxDifference(composed, patch, lattice), 1e-13);
}

TEST(BernsteinComposition, CurveIsAPatchOfDegreeZeroInV) {
  const ffd::Lattice lattice = deformedLatticeAround(kUnitBox, {2, 3, 4}, 0.2);
  const BezierPatch curve = wavyPatch(3, 0, true, 3);
  const BezierPatch composed = composeBezierPatch(BernsteinVolume::fromLattice(lattice), curve);
  EXPECT_EQ(composed.degreeU, 6 * 3);
  EXPECT_EQ(composed.degreeV, 0);
  EXPECT_LT(maxDifference(composed, curve, lattice), 1e-13);
}

TEST(BernsteinComposition, AQuarterCircleArcStaysOnTheDeformedCircle) {
  // The exact rational quadratic quarter circle of radius 0.3 about (0.5, 0.5, 0.5).
  BezierPatch arc;
  arc.degreeU = 2;
  arc.poles.resize(3, 3);
  arc.poles << 0.8, 0.5, 0.5, 0.8, 0.8, 0.5, 0.5, 0.8, 0.5;
  arc.weights = Eigen::Vector3d(1.0, std::sqrt(0.5), 1.0);
  for (int i = 0; i <= 8; ++i) EXPECT_NEAR((arc.evaluate(i / 8.0) - Eigen::Vector3d(0.5, 0.5, 0.5)).norm(), 0.3, 1e-15);
  const ffd::Lattice lattice = deformedLatticeAround(kUnitBox, {4, 2, 3}, 0.3);
  const BezierPatch composed = composeBezierPatch(BernsteinVolume::fromLattice(lattice), arc);
  EXPECT_LT(maxDifference(composed, arc, lattice), 1e-13);
}

TEST(BernsteinComposition, RestLatticeReproducesThePatch) {
  ffd::BoxLatticeOptions options;
  options.counts = {3, 3, 3};
  options.bases = {ffd::AxisBasis::bernstein(), ffd::AxisBasis::bernstein(), ffd::AxisBasis::bernstein()};
  options.boxMin = {-1, -2, 0};
  options.boxMax = {3, 2, 5};
  const ffd::Lattice lattice = ffd::makeBoxLattice(options);
  const BezierPatch patch = wavyPatch(3, 3, true, 5);
  const BezierPatch composed = composeBezierPatch(BernsteinVolume::fromLattice(lattice), patch);
  for (int i = 0; i <= 6; ++i)
    for (int j = 0; j <= 6; ++j)
      EXPECT_LT((composed.evaluate(i / 6.0, j / 6.0) - patch.evaluate(i / 6.0, j / 6.0)).norm(), 1e-14);
}

TEST(BernsteinComposition, SecondEvaluationPathAgreesWithTheLattice) {
  const ffd::Lattice lattice = deformedLatticeAround(kUnitBox, {4, 3, 2}, 0.3);
  const BernsteinVolume volume = BernsteinVolume::fromLattice(lattice);
  for (double x : {0.0, 0.37, 1.0})
    for (double y : {0.1, 0.8})
      for (double z : {0.25, 0.9}) {
        const Eigen::Vector3d q(x, y, z);
        EXPECT_LT((volume.evaluate(q) - ffdOf(lattice, q)).norm(), 1e-14);
      }
}

TEST(BernsteinComposition, RefusesABSplineLattice) {
  ffd::BoxLatticeOptions options;
  options.counts = {5, 5, 5};
  const ffd::Lattice lattice = ffd::makeBoxLattice(options);
  try {
    BernsteinVolume::fromLattice(lattice);
    FAIL() << "a B-spline lattice was accepted";
  } catch (const CadError& error) {
    EXPECT_NE(std::string(error.what()).find("Bernstein"), std::string::npos) << error.what();
  }
}

TEST(BernsteinComposition, EachCellOfABSplineLatticeIsOnePolynomial) {
  // Cubic x quadratic x linear, uneven knots on u: each cell's Bernstein form evaluates to the
  // lattice's FFD at points of that cell, and beyond the end cells to the extrapolated FFD.
  Eigen::VectorXd knots(10);
  knots << 0, 0, 0, 0, 0.2, 0.7, 1, 1, 1, 1;
  ffd::BoxLatticeOptions options;
  options.counts = {6, 4, 3};
  options.bases = {ffd::AxisBasis::bsplineWithKnots(3, knots), ffd::AxisBasis::bspline(2), ffd::AxisBasis::bspline(1)};
  ffd::Lattice lattice = ffd::makeBoxLattice(options);
  std::mt19937 rng(5);
  std::normal_distribution<double> move(0.0, 0.05);
  Eigen::MatrixX3d points = lattice.restPoints();
  for (Eigen::Index i = 0; i < points.rows(); ++i) points.row(i) += Eigen::RowVector3d(move(rng), move(rng), move(rng));
  lattice.setControlPoints(points);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int checked = 0;
  for (int ci = 0; ci < lattice.axis(0).cellCount(); ++ci)
    for (int cj = 0; cj < lattice.axis(1).cellCount(); ++cj)
      for (int ck = 0; ck < lattice.axis(2).cellCount(); ++ck) {
        const Eigen::Vector3i cell(ci, cj, ck);
        const BernsteinVolume volume = BernsteinVolume::fromLatticeCell(lattice, cell);
        EXPECT_EQ(volume.degrees, Eigen::Vector3i(3, 2, 1));
        for (int sample = 0; sample < 20; ++sample) {
          Eigen::Vector3d uvw;
          for (int a = 0; a < 3; ++a) {
            const double lo = lattice.axis(a).cellMin(cell[a]), hi = lattice.axis(a).cellMax(cell[a]);
            uvw[a] = lo + (hi - lo) * unit(rng);
          }
          const Eigen::Vector3d world = lattice.restAffineLinear() * uvw + lattice.restAffineOffset();
          EXPECT_LT((volume.evaluate(world) - ffdOf(lattice, world)).norm(), 1e-13);
          ++checked;
        }
      }
  EXPECT_EQ(checked, 3 * 2 * 2 * 20);
  // Beyond the lattice the end cell's polynomial continues (Lattice::evaluate extrapolates it).
  const Eigen::Vector3d beyond(1.2, 0.5, -0.1);
  const BernsteinVolume last = BernsteinVolume::fromLatticeCell(lattice, {2, 0, 0});
  EXPECT_LT((last.evaluate(beyond) - ffdOf(lattice, beyond)).norm(), 1e-12);
  EXPECT_THROW(BernsteinVolume::fromLatticeCell(lattice, {3, 0, 0}), CadError);
}

TEST(BernsteinComposition, RefusesNonPositiveWeightsAndWrongPoleCounts) {
  const BernsteinVolume volume = BernsteinVolume::fromLattice(deformedLatticeAround(kUnitBox, {2, 2, 2}, 0.1));
  BezierPatch patch = wavyPatch(2, 1, true, 2);
  patch.weights[3] = 0.0;
  EXPECT_THROW(composeBezierPatch(volume, patch), CadError);
  patch = wavyPatch(2, 1, false, 2);
  patch.poles.conservativeResize(4, 3);
  EXPECT_THROW(composeBezierPatch(volume, patch), CadError);
  patch = wavyPatch(2, 1, false, 2);
  patch.poles(0, 0) = std::nan("");
  EXPECT_THROW(composeBezierPatch(volume, patch), CadError);
}

}  // namespace
}  // namespace ffdkit::cad
