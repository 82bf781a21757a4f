#include "ffdkit/ffd/lattice.h"

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "reference_ffd.h"

namespace ffdkit::ffd {
namespace {

// Builds a random lattice: random bases per axis (Bernstein, clamped uniform or non-uniform
// B-spline, periodic) and random control points, together with the reference description.
struct RandomLattice {
  Eigen::Vector3i counts;
  std::array<AxisBasis, 3> bases;
  reference::Axis axes[3];
};

RandomLattice randomLatticeSpec(std::mt19937& rng, bool allowPeriodic) {
  RandomLattice r;
  std::uniform_int_distribution<int> countDist(2, 7);
  std::uniform_int_distribution<int> kindDist(0, allowPeriodic ? 3 : 2);
  for (int a = 0; a < 3; ++a) {
    const int count = countDist(rng);
    r.counts[a] = count;
    const int degree = std::uniform_int_distribution<int>(1, count - 1)(rng);
    reference::Axis& ax = r.axes[a];
    ax.count = count;
    switch (kindDist(rng)) {
      case 0:
        r.bases[a] = AxisBasis::bernstein();
        ax.kind = reference::Axis::Kind::Bernstein;
        break;
      case 1:
        r.bases[a] = AxisBasis::bspline(degree);
        ax.degree = degree;
        ax.knots = reference::clampedUniform(count, degree);
        break;
      case 2: {
        ax.degree = degree;
        ax.knots = reference::randomClamped(count, degree, rng);
        r.bases[a] = AxisBasis::bsplineWithKnots(degree, Eigen::Map<Eigen::VectorXd>(ax.knots.data(), ax.knots.size()));
        break;
      }
      default:
        r.bases[a] = AxisBasis::periodic(degree);
        ax.kind = reference::Axis::Kind::Periodic;
        ax.degree = degree;
        ax.knots = reference::periodicUniform(count, degree);
        break;
    }
  }
  return r;
}

TEST(Lattice, RejectsFewerThanTwoPointsPerAxis) {
  BoxLatticeOptions options;
  options.counts = {1, 4, 4};
  try {
    makeBoxLattice(options);
    FAIL() << "expected LatticeError";
  } catch (const LatticeError& e) {
    EXPECT_EQ(std::string(e.what()), "lattice needs >= 2 points per axis, got (1, 4, 4)");
  }
  EXPECT_THROW(Lattice({4, 0, 4}, {}, Eigen::MatrixX3d::Zero(0, 3)), LatticeError);
}

TEST(Lattice, RejectsDegreeOutOfRange) {
  BoxLatticeOptions options;
  options.capDegreeToCount = false;
  options.counts = {4, 3, 4};
  EXPECT_THROW(makeBoxLattice(options), LatticeError);  // cubic on 3 points
  options.bases[1] = AxisBasis::bspline(0);
  EXPECT_THROW(makeBoxLattice(options), LatticeError);
  options.bases[1] = AxisBasis::bspline(2);
  EXPECT_NO_THROW(makeBoxLattice(options));
}

TEST(Lattice, CapsDefaultDegreeToCountWhenAsked) {
  BoxLatticeOptions options;
  options.counts = {2, 3, 4};
  const Lattice lattice = makeBoxLattice(options);
  EXPECT_EQ(lattice.axis(0).degree(), 1);
  EXPECT_EQ(lattice.axis(1).degree(), 2);
  EXPECT_EQ(lattice.axis(2).degree(), 3);
}

TEST(Lattice, RejectsBadKnots) {
  BoxLatticeOptions options;
  options.counts = {4, 4, 4};
  Eigen::VectorXd knots(8);
  knots << 0, 0, 0, 0, 1, 1, 1;  // 7 values: wrong length (needs 8)
  options.bases[0] = AxisBasis::bsplineWithKnots(3, knots.head(7));
  EXPECT_THROW(makeBoxLattice(options), LatticeError);
  knots << 0, 0, 0, 0, 1, 1, 0.5, 1;  // decreasing
  options.bases[0] = AxisBasis::bsplineWithKnots(3, knots);
  EXPECT_THROW(makeBoxLattice(options), LatticeError);
  knots << 0, 0, 0, 0, std::numeric_limits<double>::quiet_NaN(), 1, 1, 1;
  options.bases[0] = AxisBasis::bsplineWithKnots(3, knots);
  EXPECT_THROW(makeBoxLattice(options), LatticeError);
  knots << 0, 0, 0, 0, 0, 1, 1, 1;  // a knot of multiplicity degree+2
  options.bases[0] = AxisBasis::bsplineWithKnots(3, knots);
  EXPECT_THROW(makeBoxLattice(options), LatticeError);
  knots << 0, 0, 0, 0, 1, 1, 1, 1;
  options.bases[0] = AxisBasis::bsplineWithKnots(3, knots);
  EXPECT_NO_THROW(makeBoxLattice(options));
}

TEST(Lattice, RejectsNonFiniteCoordinates) {
  Lattice lattice = makeBoxLattice();
  EXPECT_THROW(lattice.setControlPoint(3, Eigen::Vector3d(0, std::nan(""), 0)), LatticeError);
  Eigen::MatrixX3d P = lattice.controlPoints();
  P(5, 2) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(lattice.setControlPoints(P), LatticeError);
  EXPECT_THROW(Lattice(lattice.counts(), {AxisBasis::bspline(), AxisBasis::bspline(), AxisBasis::bspline()}, P),
               LatticeError);
  EXPECT_TRUE(lattice.controlPoints().allFinite());
  Eigen::Affine3d bad = Eigen::Affine3d::Identity();
  bad(0, 3) = std::nan("");
  EXPECT_THROW(lattice.setFrame(bad), LatticeError);
}

TEST(Lattice, RejectsWrongSizeAndIndex) {
  Lattice lattice = makeBoxLattice();
  EXPECT_THROW(lattice.setControlPoints(Eigen::MatrixX3d::Zero(10, 3)), LatticeError);
  EXPECT_THROW(lattice.setControlPoint(64, Eigen::Vector3d::Zero()), LatticeError);
  EXPECT_THROW(lattice.setControlPoint(-1, Eigen::Vector3d::Zero()), LatticeError);
}

TEST(Lattice, RejectsDegenerateRestLattice) {
  Lattice box = makeBoxLattice();
  Eigen::MatrixX3d flat = box.restPoints();
  flat.col(2).setConstant(0.5);  // all points in one plane: zero volume
  EXPECT_THROW(Lattice(box.counts(), {AxisBasis::bspline(), AxisBasis::bspline(), AxisBasis::bspline()}, flat),
               LatticeError);
  EXPECT_THROW(box.setRestPoints(Eigen::MatrixX3d::Zero(64, 3)), LatticeError);
  Eigen::Affine3d singular = Eigen::Affine3d::Identity();
  singular.linear()(2, 2) = 0.0;
  EXPECT_THROW(box.setFrame(singular), LatticeError);
}

TEST(Lattice, FlatIndexIsIFastestAndInvertible) {
  BoxLatticeOptions options;
  options.counts = {3, 4, 5};
  const Lattice lattice = makeBoxLattice(options);
  EXPECT_EQ(lattice.pointCount(), 60);
  EXPECT_EQ(lattice.index(1, 0, 0), 1);
  EXPECT_EQ(lattice.index(0, 1, 0), 3);
  EXPECT_EQ(lattice.index(0, 0, 1), 12);
  for (Eigen::Index f = 0; f < lattice.pointCount(); ++f) {
    const Eigen::Vector3i g = lattice.gridIndex(f);
    EXPECT_EQ(lattice.index(g[0], g[1], g[2]), f);
  }
}

TEST(Lattice, BoxRestPointsFillTheBoxAndRestMapIsAffine) {
  for (auto basis : {AxisBasis::bernstein(), AxisBasis::bspline(1), AxisBasis::bspline(2), AxisBasis::bspline(3)}) {
    BoxLatticeOptions options;
    options.counts = {5, 4, 6};
    options.bases = {basis, basis, basis};
    options.boxMin = {-1, 2, 0};
    options.boxMax = {3, 2.5, 7};
    const Lattice lattice = makeBoxLattice(options);
    EXPECT_TRUE(lattice.restIsAffine());
    EXPECT_TRUE(lattice.restPoints().colwise().minCoeff().transpose().isApprox(options.boxMin, 1e-15));
    EXPECT_TRUE(lattice.restPoints().colwise().maxCoeff().transpose().isApprox(options.boxMax, 1e-15));
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    for (int s = 0; s < 50; ++s) {
      const Eigen::Vector3d uvw(U(rng), U(rng), U(rng));
      const Eigen::Vector3d expected = options.boxMin + (options.boxMax - options.boxMin).cwiseProduct(uvw);
      EXPECT_LT((lattice.evaluateRest(uvw) - expected).norm(), 1e-12);
      EXPECT_LT((lattice.restAffineLinear() * uvw + lattice.restAffineOffset() - expected).norm(), 1e-12);
    }
  }
}

TEST(Lattice, BernsteinBoxIsRegularGrid) {
  BoxLatticeOptions options;
  options.counts = {3, 4, 5};
  options.bases = {AxisBasis::bernstein(), AxisBasis::bernstein(), AxisBasis::bernstein()};
  const Lattice lattice = makeBoxLattice(options);
  for (Eigen::Index f = 0; f < lattice.pointCount(); ++f) {
    const Eigen::Vector3i g = lattice.gridIndex(f);
    const Eigen::Vector3d expected(g[0] / 2.0, g[1] / 3.0, g[2] / 4.0);
    EXPECT_LT((lattice.restPoints().row(f).transpose() - expected).norm(), 1e-15);
  }
}

TEST(Lattice, MatchesReferenceEvaluatorOnRandomLattices) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    const RandomLattice spec = randomLatticeSpec(rng, true);
    Eigen::MatrixX3d P = Eigen::MatrixX3d::Random(spec.counts.prod(), 3);
    // Any rest shape with volume works; evaluation of P is what is compared.
    Eigen::MatrixX3d rest(spec.counts.prod(), 3);
    for (Eigen::Index f = 0; f < rest.rows(); ++f) {
      rest.row(f) << f % spec.counts[0], (f / spec.counts[0]) % spec.counts[1], f / (spec.counts[0] * spec.counts[1]);
    }
    Lattice lattice(spec.counts, spec.bases, rest);
    lattice.setControlPoints(P);
    for (int s = 0; s < 30; ++s) {
      Eigen::Vector3d uvw;
      for (int a = 0; a < 3; ++a) {
        const double lo = lattice.parameterMin()[a];
        const double hi = lattice.parameterMax()[a];
        uvw[a] = s == 0 ? lo : s == 1 ? hi : lo + (hi - lo) * U(rng);
      }
      const Eigen::Vector3d expected = reference::evaluate(spec.axes, P, uvw);
      EXPECT_LT((lattice.evaluate(uvw) - expected).norm(), 1e-12 * (1.0 + expected.norm()))
          << "trial " << trial << " uvw " << uvw.transpose();
    }
  }
}

TEST(Lattice, PartitionOfUnityAndAffineInvariance) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const RandomLattice spec = randomLatticeSpec(rng, true);
    Eigen::MatrixX3d rest(spec.counts.prod(), 3);
    for (Eigen::Index f = 0; f < rest.rows(); ++f) {
      rest.row(f) << f % spec.counts[0], (f / spec.counts[0]) % spec.counts[1], f / (spec.counts[0] * spec.counts[1]);
    }
    rest += 0.2 * Eigen::MatrixX3d::Random(rest.rows(), 3);
    Lattice lattice(spec.counts, spec.bases, rest);
    Eigen::Affine3d T = Eigen::Affine3d::Identity();
    T.linear() = Eigen::Matrix3d::Random() + 2.0 * Eigen::Matrix3d::Identity();
    T.translation() = Eigen::Vector3d::Random();
    lattice.setControlPoints((rest * T.linear().transpose()).rowwise() + T.translation().transpose());
    for (int s = 0; s < 20; ++s) {
      Eigen::Vector3d uvw;
      for (int a = 0; a < 3; ++a) {
        uvw[a] = lattice.parameterMin()[a] + (lattice.parameterMax()[a] - lattice.parameterMin()[a]) * U(rng);
      }
      const Eigen::Vector3d expected = T * lattice.evaluateRest(uvw);
      EXPECT_LT((lattice.evaluate(uvw) - expected).norm(), 1e-12 * (1.0 + expected.norm()));
    }
    // Partition of unity: a pure translation of every control point translates X by the same vector.
    const Eigen::RowVector3d shift(0.3, -1.2, 2.5);
    lattice.setControlPoints(rest.rowwise() + shift);
    const Eigen::Vector3d uvw = 0.5 * (lattice.parameterMin() + lattice.parameterMax());
    EXPECT_LT((lattice.evaluate(uvw) - lattice.evaluateRest(uvw) - shift.transpose()).norm(), 1e-12);
  }
}

TEST(Lattice, JacobianMatchesFiniteDifferences) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 10; ++trial) {
    const RandomLattice spec = randomLatticeSpec(rng, true);
    Eigen::MatrixX3d rest(spec.counts.prod(), 3);
    for (Eigen::Index f = 0; f < rest.rows(); ++f) {
      rest.row(f) << f % spec.counts[0], (f / spec.counts[0]) % spec.counts[1], f / (spec.counts[0] * spec.counts[1]);
    }
    Lattice lattice(spec.counts, spec.bases, rest);
    lattice.setControlPoints(Eigen::MatrixX3d::Random(rest.rows(), 3));
    const Eigen::Vector3d uvw = lattice.parameterMin() + 0.37 * (lattice.parameterMax() - lattice.parameterMin());
    const Eigen::Matrix3d J = lattice.jacobian(uvw);
    for (int a = 0; a < 3; ++a) {
      const double h = 1e-6;
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      e[a] = h;
      const Eigen::Vector3d fd = (lattice.evaluate(uvw + e) - lattice.evaluate(uvw - e)) / (2 * h);
      EXPECT_LT((J.col(a) - fd).norm(), 1e-6 * (1.0 + fd.norm()));
    }
  }
}

TEST(Lattice, RevisionsTrackEdits) {
  Lattice lattice = makeBoxLattice();
  const auto r0 = lattice.revision();
  const auto rr0 = lattice.restRevision();
  lattice.setControlPoint(0, Eigen::Vector3d(-0.1, 0, 0));
  EXPECT_NE(lattice.revision(), r0);
  EXPECT_EQ(lattice.restRevision(), rr0);
  Lattice copy = lattice;
  copy.setControlPoint(1, Eigen::Vector3d(0.2, 0, 0));
  EXPECT_NE(copy.revision(), lattice.revision());
  Eigen::Affine3d frame = Eigen::Affine3d::Identity();
  frame.translate(Eigen::Vector3d(1, 2, 3));
  lattice.setFrame(frame);
  EXPECT_NE(lattice.restRevision(), rr0);
  EXPECT_TRUE(lattice.frame().isApprox(frame));
  lattice.resetToRest();
  EXPECT_TRUE(lattice.controlPoints().isApprox(lattice.restPoints()));
}

TEST(Lattice, SetOutsidePolicyValidatesFalloffDistance) {
  Lattice lattice = makeBoxLattice();
  EXPECT_THROW(lattice.setOutsidePolicy(OutsidePolicy::falloff(0.0)), LatticeError);
  EXPECT_NO_THROW(lattice.setOutsidePolicy(OutsidePolicy::falloff(0.5)));
  EXPECT_EQ(lattice.outsidePolicy(), OutsidePolicy::falloff(0.5));
}

}  // namespace
}  // namespace ffdkit::ffd
