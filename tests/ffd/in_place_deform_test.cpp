// deformInPlace against what it replaces: embed() of the whole array and Deformer::deform(), bit
// for bit, for affine (closed-form) and user-shaped (Newton) rest lattices, both precisions and the
// outside policies; its chunking, progress, cancel and non-finite input.
#include "ffdkit/ffd/in_place_deform.h"

#include <gtest/gtest.h>

#include <random>

#include "test_lattices.h"

namespace ffdkit::ffd {
namespace {

// n points in the lattice's box grown by a tenth on each side (some outside), in world coordinates.
Eigen::MatrixX3d pointsAround(const Lattice& lattice, Eigen::Index n, unsigned seed) {
  Eigen::MatrixX3d box = testing::uniformPointsInUnitBox(n, seed).array() * 1.2 - 0.1;
  const Eigen::Vector3d lo(-1.0, -0.5, 0.0), size(2.0, 2.0, 0.5);  // testing::randomLattice's box
  Eigen::MatrixX3d world(n, 3);
  for (Eigen::Index r = 0; r < n; ++r)
    world.row(r) = (lattice.frame() * (lo + size.cwiseProduct(box.row(r).transpose()))).transpose();
  return world;
}

void moveControlPoints(Lattice& lattice, std::mt19937& rng) {
  std::uniform_real_distribution<double> U(-0.2, 0.2);
  Eigen::MatrixX3d control = lattice.controlPoints();
  for (Eigen::Index r = 0; r < control.rows(); ++r)
    for (int c = 0; c < 3; ++c) control(r, c) += U(rng);
  lattice.setControlPoints(control);
}

// What deformInPlace replaces: one embedding of every point and one Deformer pass.
Eigen::MatrixX3d deformedWhole(const Lattice& lattice, const Eigen::MatrixX3d& points, Precision precision) {
  Deformer deformer(embed(lattice, points));
  deformer.setPrecision(precision);
  return deformer.deform(lattice, points);
}

InPlaceDeformOptions chunksOf(Eigen::Index points, Precision precision = Precision::Double) {
  InPlaceDeformOptions options;
  options.chunkPoints = points;
  options.precision = precision;
  return options;
}

void expectSameBits(const Eigen::MatrixX3d& expected, const Eigen::MatrixX3d& got) {
  ASSERT_EQ(expected.rows(), got.rows());
  Eigen::Index differ = 0, first = -1;
  for (Eigen::Index r = 0; r < got.rows(); ++r)
    if (got.row(r) != expected.row(r)) {
      if (first < 0) first = r;
      ++differ;
    }
  EXPECT_EQ(differ, 0) << "first differing row " << first;
}

TEST(DeformInPlace, EqualsEmbedAndDeformBitForBitOnAffineAndUserShapedLattices) {
  for (unsigned seed : {1u, 2u, 3u, 4u}) {
    std::mt19937 rng(seed);
    Lattice lattice = testing::randomLattice(rng, seed % 2 == 0 ? 0.0 : 0.15);
    moveControlPoints(lattice, rng);
    SCOPED_TRACE("seed " + std::to_string(seed) + (lattice.restIsAffine() ? ", affine rest" : ", user-shaped rest"));
    // Three chunks of the smallest size and a last one merged with what is left.
    const Eigen::Index n = 3 * kInPlaceMinChunk + 4096 * 5 + 17;
    const Eigen::MatrixX3d points = pointsAround(lattice, n, seed);
    Eigen::MatrixX3d inPlace = points;
    const InPlaceDeformResult result = deformInPlace(lattice, inPlace, chunksOf(1000));
    expectSameBits(deformedWhole(lattice, points, Precision::Double), inPlace);
    const Embedding whole = embed(lattice, points);
    EXPECT_EQ(result.insidePoints, whole.insideCount());
    EXPECT_EQ(result.outsidePoints, whole.outsideCount());
    EXPECT_EQ(result.failedPoints, whole.failedCount());
    EXPECT_GT(result.outsidePoints, 0);
    EXPECT_GT(result.embedSeconds, 0.0);
  }
}

TEST(DeformInPlace, SinglePrecisionAndOutsidePoliciesGiveTheDeformersBits) {
  std::mt19937 rng(7);
  Lattice lattice = testing::randomLattice(rng, 0.0);
  moveControlPoints(lattice, rng);
  const Eigen::MatrixX3d points = pointsAround(lattice, 2 * kInPlaceMinChunk + 999, 7);
  for (OutsidePolicy policy : {OutsidePolicy::identity(), OutsidePolicy::clampEdge(), OutsidePolicy::extrapolate(),
                               OutsidePolicy::falloff(0.3)}) {
    lattice.setOutsidePolicy(policy);
    for (Precision precision : {Precision::Double, Precision::Single}) {
      Eigen::MatrixX3d inPlace = points;
      deformInPlace(lattice, inPlace, chunksOf(kInPlaceMinChunk, precision));
      expectSameBits(deformedWhole(lattice, points, precision), inPlace);
    }
  }
}

TEST(DeformInPlace, ASmallArrayInABlockOfALargerMatrixLeavesTheRestAlone) {
  std::mt19937 rng(11);
  Lattice lattice = testing::randomLattice(rng, 0.1);
  moveControlPoints(lattice, rng);
  const Eigen::MatrixX3d points = pointsAround(lattice, 5000, 11);
  Eigen::MatrixX3d all = Eigen::MatrixX3d::Zero(7000, 3);
  all.middleRows(1000, 5000) = points;
  deformInPlace(lattice, all.middleRows(1000, 5000));
  expectSameBits(deformedWhole(lattice, points, Precision::Double), all.middleRows(1000, 5000));
  EXPECT_TRUE(all.topRows(1000).isZero(0.0));
  EXPECT_TRUE(all.bottomRows(1000).isZero(0.0));
}

TEST(DeformInPlace, ProgressCoversTheWholeArrayAndCancelStopsBetweenChunks) {
  std::mt19937 rng(5);
  Lattice lattice = testing::randomLattice(rng, 0.0);
  moveControlPoints(lattice, rng);
  const Eigen::Index n = 3 * kInPlaceMinChunk;
  const Eigen::MatrixX3d points = pointsAround(lattice, n, 5);
  Eigen::MatrixX3d moved = points;
  std::vector<std::pair<Eigen::Index, Eigen::Index>> calls;
  InPlaceDeformOptions options;
  options.chunkPoints = kInPlaceMinChunk;
  options.embed.progress = [&calls](Eigen::Index done, Eigen::Index total) {
    calls.emplace_back(done, total);
    return true;
  };
  deformInPlace(lattice, moved, options);
  ASSERT_FALSE(calls.empty());
  EXPECT_EQ(calls.front(), std::make_pair(Eigen::Index(0), n));
  EXPECT_EQ(calls.back(), std::make_pair(n, n));
  for (std::size_t i = 1; i < calls.size(); ++i) EXPECT_GE(calls[i].first, calls[i - 1].first);

  // Cancelled once the first chunk is done: it is deformed, the later chunks are as given.
  Eigen::MatrixX3d cancelled = points;
  options.embed.progress = [](Eigen::Index done, Eigen::Index) { return done < kInPlaceMinChunk + 1; };
  EXPECT_THROW(deformInPlace(lattice, cancelled, options), Cancelled);
  expectSameBits(moved.topRows(kInPlaceMinChunk), cancelled.topRows(kInPlaceMinChunk));
  expectSameBits(points.bottomRows(kInPlaceMinChunk), cancelled.bottomRows(kInPlaceMinChunk));
}

TEST(DeformInPlace, NamesANonFinitePointByItsRow) {
  std::mt19937 rng(9);
  const Lattice lattice = testing::randomLattice(rng, 0.0);
  Eigen::MatrixX3d points = pointsAround(lattice, 2 * kInPlaceMinChunk + 10, 9);
  points(kInPlaceMinChunk + 3, 1) = std::numeric_limits<double>::quiet_NaN();
  try {
    deformInPlace(lattice, points, chunksOf(kInPlaceMinChunk));
    FAIL() << "no throw";
  } catch (const LatticeError& e) {
    EXPECT_NE(std::string(e.what()).find("point " + std::to_string(kInPlaceMinChunk + 3) + " is not finite"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace ffdkit::ffd
