#include "ffdkit/geometry/curvenet/run_fairing.h"

#include <gtest/gtest.h>

#include "continuity_check.h"
#include "ffdkit/geometry/curvenet/example_networks.h"
#include "ffdkit/geometry/curvenet/multisided_patch.h"

namespace ffdkit::geometry::curvenet {
namespace {

TEST(RunFairing, ZeroCoefficientsEqualTheParallelSweepWithEqualWeights) {  // P14
  const CurveNetwork plain = buildCurveNetwork(heightGridNetwork(3));
  CurveNetwork affine = plain;
  for (curvenet::Run& r : affine.runs) r.affine = true;  // c = 0
  for (int f = 0; f < static_cast<int>(plain.faces.size()); ++f) {
    const NGonDomain d(4);
    for (double x : {-0.5, 0.1, 0.6}) {
      for (double y : {-0.4, 0.2, 0.55}) {
        const VectorJet a = evaluatePatch(plain, f, d, {x, y}), b = evaluatePatch(affine, f, d, {x, y});
        EXPECT_LE((a.v - b.v).norm(), 1e-13);
        EXPECT_LE((a.xx - b.xx).norm(), 1e-10);
      }
    }
  }
}

TEST(RunFairing, OptimumLowersEnergyAndKeepsInterpolationAndG2) {  // P14
  CurveNetwork net = buildCurveNetwork(heightGridNetwork(4));
  const FairingResult result = fairRunSweeps(net);
  ASSERT_FALSE(result.runs.empty());
  bool changed = false;
  for (const RunFairing& r : result.runs) {
    EXPECT_LE(r.energyAfter, r.energyBefore * (1 + 1e-12) + 1e-14);
    // The closed-form value agrees with the public energy function.
    const curvenet::Run& run = net.runs[r.run];
    EXPECT_NEAR(runFairingEnergy(net, r.run, run.cStart, run.cEnd), r.energyAfter, 1e-9 * (1 + r.energyBefore));
    EXPECT_NEAR(runFairingEnergy(net, r.run, Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()), r.energyBefore,
                1e-9 * (1 + r.energyBefore));
    changed = changed || run.cStart.norm() + run.cEnd.norm() > 1e-9;
  }
  EXPECT_TRUE(changed);
  EXPECT_LT(result.totalAfter, result.totalBefore);
  const auto m = testing::sharedEdgeMismatch(net);
  EXPECT_LE(m.boundary, 1e-12 * net.scale) << "P1";
  EXPECT_LE(m.position, 1e-12 * net.scale) << "P4";
  EXPECT_LE(m.angle, 1e-9) << "G1 kept: M is shared";
  EXPECT_LE(m.curvature, 1e-8) << "G2 kept";
}

TEST(RunFairing, RejectsTooFewQuadraturePoints) {
  CurveNetwork net = buildCurveNetwork(sphereOctantNetwork());
  FairingOptions o;
  o.quadraturePoints = 2;
  EXPECT_THROW(fairRunSweeps(net, o), std::invalid_argument);
}

}  // namespace
}  // namespace ffdkit::geometry::curvenet
