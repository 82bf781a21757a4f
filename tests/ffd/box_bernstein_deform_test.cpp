#include "ffdkit/ffd/box_bernstein_deform.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "ffdkit/ffd/deformer.h"
#include "ffdkit/ffd/embedding.h"
#include "ffdkit/ffd/lattice.h"
#include "ffdkit/ffd/lattice_error.h"
#include "reference_ffd.h"
#include "test_lattices.h"

namespace ffdkit::ffd {
namespace {

using ColumnMap = Eigen::Map<const PointRows, 0, PointRowsStride>;
using ColumnMapOut = Eigen::Map<PointRows, 0, PointRowsStride>;

// A column-major N x 3 matrix seen as strided rows (row stride 1, column stride N).
ColumnMap rowsOf(const Eigen::MatrixX3d& m) { return ColumnMap(m.data(), m.rows(), 3, PointRowsStride(1, m.rows())); }
ColumnMapOut rowsOf(Eigen::MatrixX3d& m) { return ColumnMapOut(m.data(), m.rows(), 3, PointRowsStride(1, m.rows())); }

Eigen::MatrixX3d deformed(const BoxBernsteinLattice& lattice, const Eigen::MatrixX3d& points,
                          BoxBernsteinDeformOptions options = {}, Eigen::Index* inside = nullptr) {
  Eigen::MatrixX3d out(points.rows(), 3);
  const BoxBernsteinDeformResult result = boxBernsteinDeform(lattice, rowsOf(points), rowsOf(out), options);
  if (inside) *inside = result.insidePoints;
  return out;
}

// The independent evaluator: the textbook triple sum over every control point (reference_ffd.h,
// binomial Bernstein formula) of the displaced rest lattice X_ijk + d_ijk at the box
// coordinates s, mapped to the world by the frame (Sederberg & Parry 1986, eq. 1).
Eigen::Vector3d referencePoint(const BoxBernsteinLattice& lattice, const Eigen::Vector3d& s) {
  reference::Axis axes[3];
  for (int a = 0; a < 3; ++a) {
    axes[a].kind = reference::Axis::Kind::Bernstein;
    axes[a].count = lattice.counts[a];
    axes[a].degree = lattice.counts[a] - 1;
  }
  const int l = lattice.counts[0], m = lattice.counts[1], n = lattice.counts[2];
  Eigen::MatrixX3d P(l * m * n, 3);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < l; ++i) {
        const int r = i + l * (j + m * k);
        P.row(r) << double(i) / (l - 1), double(j) / (m - 1), double(k) / (n - 1);
        if (lattice.displacements.rows()) P.row(r) += lattice.displacements.row(r);
      }
  return lattice.frame * reference::evaluate(axes, P, s);
}

BoxBernsteinLattice randomLattice(const Eigen::Vector3i& counts, std::mt19937& rng, double amount = 0.3) {
  std::normal_distribution<double> N(0.0, amount);
  BoxBernsteinLattice lattice;
  lattice.counts = counts;
  lattice.frame = testing::randomFrame(rng);
  lattice.displacements.resize(counts.prod(), 3);
  for (Eigen::Index r = 0; r < lattice.displacements.rows(); ++r)
    for (int c = 0; c < 3; ++c) lattice.displacements(r, c) = N(rng);
  return lattice;
}

// Box coordinates uniform in [-0.2, 1.2]^3 (about 40 % of the points outside), and their world points.
void randomPoints(const BoxBernsteinLattice& lattice, Eigen::Index n, std::mt19937& rng, Eigen::MatrixX3d& s,
                  Eigen::MatrixX3d& q) {
  std::uniform_real_distribution<double> U(-0.2, 1.2);
  s.resize(n, 3);
  q.resize(n, 3);
  for (Eigen::Index r = 0; r < n; ++r) {
    s.row(r) << U(rng), U(rng), U(rng);
    q.row(r) = (lattice.frame * s.row(r).transpose()).transpose();
  }
}

bool insideBox(const Eigen::Vector3d& s) { return (s.array() >= 0.0).all() && (s.array() <= 1.0).all(); }

double scaleOf(const Eigen::MatrixX3d& q) { return std::max(1.0, q.cwiseAbs().maxCoeff()); }

void expectMatchesReference(const BoxBernsteinLattice& lattice, Eigen::Index n, unsigned seed) {
  std::mt19937 rng(seed);
  Eigen::MatrixX3d s, q;
  randomPoints(lattice, n, rng, s, q);
  Eigen::Index inside = -1;
  const Eigen::MatrixX3d out = deformed(lattice, q, {}, &inside);
  const double tolerance = 1e-12 * scaleOf(q);
  Eigen::Index expectedInside = 0;
  for (Eigen::Index r = 0; r < n; ++r) {
    const Eigen::Vector3d sr = s.row(r).transpose();
    if (insideBox(sr)) {
      ++expectedInside;
      const Eigen::Vector3d expected = referencePoint(lattice, sr);
      ASSERT_LE((out.row(r).transpose() - expected).cwiseAbs().maxCoeff(), tolerance)
          << "point " << r << " at s = " << sr.transpose();
    } else {
      ASSERT_EQ(out.row(r), q.row(r)) << "outside point " << r << " must come back bit for bit";
    }
  }
  EXPECT_EQ(inside, expectedInside);
  EXPECT_GT(expectedInside, n / 5);
  EXPECT_LT(expectedInside, n - n / 5);
}

TEST(BoxBernsteinDeform, MatchesTheTripleSumInRotatedBoxesWithNonCubicCounts) {
  std::mt19937 rng(11);
  expectMatchesReference(randomLattice({2, 3, 5}, rng), 3000, 1);
  expectMatchesReference(randomLattice({5, 2, 3}, rng), 3000, 2);
  expectMatchesReference(randomLattice({7, 4, 2}, rng), 3000, 3);
}

TEST(BoxBernsteinDeform, MatchesTheTripleSumForEqualCounts) {
  // 2..5 run compile-time unrolled kernels, 6 the generic one.
  std::mt19937 rng(12);
  for (int c = 2; c <= 6; ++c) {
    SCOPED_TRACE(c);
    expectMatchesReference(randomLattice({c, c, c}, rng), 2000, 10 + c);
  }
}

TEST(BoxBernsteinDeform, BlocksOfInsidePointsAndSortedPointsMatchTheTripleSum) {
  // All inside: every block of eight is summed in place. Sorted along x: most blocks are all
  // inside or all outside, the blocks at the faces mixed (queued).
  std::mt19937 rng(17);
  for (const Eigen::Vector3i& counts : {Eigen::Vector3i(4, 4, 4), Eigen::Vector3i(2, 3, 5)}) {
    const BoxBernsteinLattice lattice = randomLattice(counts, rng);
    for (const double grow : {0.0, 0.2}) {
      std::uniform_real_distribution<double> U(-grow, 1.0 + grow);
      Eigen::MatrixX3d s(4001, 3);
      for (Eigen::Index r = 0; r < s.rows(); ++r) s.row(r) << U(rng), U(rng), U(rng);
      if (grow > 0.0) {
        std::vector<Eigen::Index> order(s.rows());
        for (Eigen::Index r = 0; r < s.rows(); ++r) order[r] = r;
        std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return s(a, 0) < s(b, 0); });
        const Eigen::MatrixX3d unsorted = s;
        for (Eigen::Index r = 0; r < s.rows(); ++r) s.row(r) = unsorted.row(order[r]);
      }
      Eigen::MatrixX3d q(s.rows(), 3);
      for (Eigen::Index r = 0; r < s.rows(); ++r) q.row(r) = (lattice.frame * s.row(r).transpose()).transpose();
      const Eigen::MatrixX3d out = deformed(lattice, q);
      for (Eigen::Index r = 0; r < s.rows(); ++r) {
        const Eigen::Vector3d sr = s.row(r).transpose();
        if (insideBox(sr)) {
          ASSERT_LE((out.row(r).transpose() - referencePoint(lattice, sr)).cwiseAbs().maxCoeff(), 1e-12 * scaleOf(q))
              << "point " << r;
        } else {
          ASSERT_EQ(out.row(r), q.row(r)) << "outside point " << r;
        }
      }
    }
  }
}

TEST(BoxBernsteinDeform, AgreesWithTheEmbeddingAndDeformerPath) {
  std::mt19937 rng(13);
  const BoxBernsteinLattice box = randomLattice({4, 3, 5}, rng, 0.2);
  Lattice lattice = toLattice(box);
  Eigen::MatrixX3d s, q;
  randomPoints(box, 20000, rng, s, q);
  EmbedOptions embedOptions;
  embedOptions.boundaryEpsilon = 1e-12;
  Deformer deformer(embed(lattice, q, embedOptions));
  const Eigen::MatrixX3d expected = deformer.deform(lattice, q);
  const Eigen::MatrixX3d out = deformed(box, q);
  EXPECT_LE((out - expected).cwiseAbs().maxCoeff(), 1e-12 * scaleOf(q));
}

TEST(BoxBernsteinDeform, PointsOnFacesEdgesAndCornersAreDeformedAndJustOutsideAreNot) {
  BoxBernsteinLattice lattice;
  lattice.counts = {3, 3, 3};
  lattice.frame = Eigen::Affine3d(Eigen::Translation3d(1.0, -2.0, 0.5)) * Eigen::Scaling(1.0, 2.0, 4.0);  // exact box coordinates
  lattice.displacements = Eigen::MatrixX3d::Zero(27, 3);
  lattice.displacements(2 + 3 * (1 + 3 * 1), 0) = 0.25;  // control point (2, 1, 1), on the face x = 1
  lattice.displacements(1 + 3 * (1 + 3 * 0), 2) = -0.5;  // (1, 1, 0), on the face z = 0
  lattice.displacements(2 + 3 * (2 + 3 * 2), 1) = 0.125;  // the corner (2, 2, 2)
  const std::vector<Eigen::Vector3d> onBoundary = {{1.0, 0.5, 0.5}, {0.5, 0.5, 0.0}, {1.0, 1.0, 1.0},
                                                   {0.0, 0.0, 0.0}, {0.5, 1.0, 0.25}, {1.0, 0.5, 1.0}};
  Eigen::MatrixX3d q(2 * onBoundary.size(), 3);
  for (std::size_t p = 0; p < onBoundary.size(); ++p) {
    q.row(p) = (lattice.frame * onBoundary[p]).transpose();
    // Just outside: 1e-9 beyond the face along an axis that is at 0 or 1.
    Eigen::Vector3d out = onBoundary[p];
    for (int a = 0; a < 3; ++a) {
      if (out[a] == 1.0) { out[a] += 1e-9; break; }
      if (out[a] == 0.0) { out[a] -= 1e-9; break; }
    }
    q.row(onBoundary.size() + p) = (lattice.frame * out).transpose();
  }
  Eigen::Index inside = 0;
  const Eigen::MatrixX3d out = deformed(lattice, q, {}, &inside);
  EXPECT_EQ(inside, Eigen::Index(onBoundary.size()));
  for (std::size_t p = 0; p < onBoundary.size(); ++p) {
    const Eigen::Vector3d expected = referencePoint(lattice, onBoundary[p]);
    EXPECT_LE((out.row(p).transpose() - expected).norm(), 1e-12 * 4) << "boundary point " << p;
    EXPECT_EQ(out.row(onBoundary.size() + p), q.row(onBoundary.size() + p)) << "just outside " << p;
  }
  // (1, 1/2, 1/2): B_2(1) B_1(1/2) B_1(1/2) = 1/4 of control point (2, 1, 1)'s 0.25 along x.
  EXPECT_DOUBLE_EQ(out(0, 0), 1.0 + 1.0 + 0.25 * 0.25);
  // The corner moves by the whole displacement of the corner control point (0.125 * 2 along y).
  EXPECT_DOUBLE_EQ(out(2, 1), -2.0 + 2.0 + 0.25);
  // The box coordinates here are exact: the points on the boundary count as inside without the tolerance too.
  BoxBernsteinDeformOptions exact;
  exact.faceTolerance = 0.0;
  EXPECT_EQ(deformed(lattice, q, exact), out);
}

TEST(BoxBernsteinDeform, ZeroDisplacementsLeaveEveryPointUnchanged) {
  std::mt19937 rng(14);
  BoxBernsteinLattice lattice = randomLattice({4, 4, 4}, rng);
  Eigen::MatrixX3d s, q;
  randomPoints(lattice, 5000, rng, s, q);
  lattice.displacements.setZero();
  Eigen::Index inside = 0;
  EXPECT_EQ(deformed(lattice, q, {}, &inside), q);
  EXPECT_GT(inside, 0);
  lattice.displacements.resize(0, 3);  // empty: all zero
  EXPECT_EQ(deformed(lattice, q), q);
}

TEST(BoxBernsteinDeform, SparseDisplacementsMatchTheTripleSum) {
  // One non-zero control point (one (j, k) row), then one full row and a lone point elsewhere.
  std::mt19937 rng(15);
  BoxBernsteinLattice lattice = randomLattice({4, 3, 5}, rng);
  lattice.displacements.setZero();
  lattice.displacements.row(1 + 4 * (2 + 3 * 3)) << 0.3, -0.2, 0.1;
  expectMatchesReference(lattice, 2000, 21);
  lattice.displacements.middleRows(4 * (0 + 3 * 1), 4).setConstant(-0.15);
  lattice.displacements(3 + 4 * (1 + 3 * 4), 2) = 0.4;
  expectMatchesReference(lattice, 2000, 22);
}

TEST(BoxBernsteinDeform, LayoutsThreadsAndInPlaceGiveTheSameBits) {
  std::mt19937 rng(16);
  const BoxBernsteinLattice lattice = randomLattice({4, 4, 4}, rng);
  Eigen::MatrixX3d s, q;
  randomPoints(lattice, 100003, rng, s, q);  // several chunks, a partial last block
  const Eigen::MatrixX3d columnMajor = deformed(lattice, q);

  const PointRows rowMajorIn = q;  // numpy's C order
  PointRows rowMajorOut(q.rows(), 3);
  boxBernsteinDeform(lattice, rowMajorIn, rowMajorOut);
  EXPECT_EQ(Eigen::MatrixX3d(rowMajorOut), columnMajor);

  BoxBernsteinDeformOptions serial;
  serial.parallel = false;
  EXPECT_EQ(deformed(lattice, q, serial), columnMajor);

  PointRows inPlace = q;
  const BoxBernsteinDeformResult result = boxBernsteinDeform(lattice, inPlace, inPlace);
  EXPECT_EQ(Eigen::MatrixX3d(inPlace), columnMajor);
  Eigen::Index inside = 0;
  for (Eigen::Index r = 0; r < s.rows(); ++r) inside += insideBox(s.row(r).transpose());
  EXPECT_EQ(result.insidePoints, inside);

  // Every other row of a bigger array (row stride 6).
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> wide(2 * q.rows(), 3);
  for (Eigen::Index r = 0; r < q.rows(); ++r) wide.row(2 * r) = q.row(r);
  Eigen::Map<const PointRows, 0, PointRowsStride> everyOther(wide.data(), q.rows(), 3, PointRowsStride(6, 1));
  PointRows out(q.rows(), 3);
  boxBernsteinDeform(lattice, everyOther, out);
  EXPECT_EQ(Eigen::MatrixX3d(out), columnMajor);
}

TEST(BoxBernsteinDeform, NonFinitePointsAreOutsideAndEmptyInputIsFine) {
  BoxBernsteinLattice lattice;
  lattice.counts = {2, 2, 2};
  lattice.displacements = Eigen::MatrixX3d::Constant(8, 3, 0.1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  Eigen::MatrixX3d q(3, 3);
  q << nan, 0.5, 0.5, 0.5, inf, 0.5, 0.5, 0.5, 0.5;
  Eigen::Index inside = 0;
  const Eigen::MatrixX3d out = deformed(lattice, q, {}, &inside);
  EXPECT_EQ(inside, 1);
  EXPECT_TRUE(std::isnan(out(0, 0)));
  EXPECT_EQ(out.row(0).tail(2), q.row(0).tail(2));
  EXPECT_EQ(out.row(1), q.row(1));
  EXPECT_TRUE(out.row(2).isApprox(Eigen::RowVector3d(0.6, 0.6, 0.6), 1e-15));
  EXPECT_EQ(deformed(lattice, Eigen::MatrixX3d(0, 3)).rows(), 0);
}

TEST(BoxBernsteinDeform, RejectsBadLatticesOptionsAndOutput) {
  BoxBernsteinLattice lattice;
  Eigen::MatrixX3d q = Eigen::MatrixX3d::Constant(4, 3, 0.5);
  auto throwsWith = [&](const BoxBernsteinLattice& l, const std::string& text, BoxBernsteinDeformOptions options = {},
                        Eigen::Index outRows = 4) {
    Eigen::MatrixX3d out(outRows, 3);
    try {
      boxBernsteinDeform(l, rowsOf(q), rowsOf(out), options);
      ADD_FAILURE() << "expected LatticeError containing '" << text << "'";
    } catch (const LatticeError& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  lattice.counts = {1, 4, 4};
  throwsWith(lattice, "needs 2 to 33 points per axis, got (1, 4, 4)");
  lattice.counts = {4, 34, 4};
  throwsWith(lattice, "got (4, 34, 4)");
  lattice.counts = {2, 3, 2};
  lattice.displacements = Eigen::MatrixX3d::Zero(8, 3);
  throwsWith(lattice, "expected 12 x 3 displacements for counts (2, 3, 2), got 8 x 3");
  lattice.displacements = Eigen::MatrixX3d::Zero(12, 3);
  lattice.displacements(1 + 2 * (2 + 3 * 1), 1) = std::numeric_limits<double>::quiet_NaN();
  throwsWith(lattice, "displacement 11 (i 1, j 2, k 1) is not finite");
  lattice.displacements.setZero();
  lattice.frame = Eigen::Scaling(1.0, 0.0, 1.0);
  throwsWith(lattice, "frame is singular");
  lattice.frame.setIdentity();
  lattice.frame.translation().x() = std::numeric_limits<double>::infinity();
  throwsWith(lattice, "frame is not finite");
  lattice.frame.setIdentity();
  BoxBernsteinDeformOptions negative;
  negative.faceTolerance = -1e-3;
  throwsWith(lattice, "faceTolerance must be finite and >= 0", negative);
  throwsWith(lattice, "out has 3 rows, expected 4", {}, 3);
}

}  // namespace
}  // namespace ffdkit::ffd
