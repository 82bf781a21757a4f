#include "ffdkit/geometry/curvenet/ngon_domain.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace ffdkit::geometry::curvenet {
namespace {

std::vector<Eigen::Vector2d> interiorGrid(const NGonDomain& d) {
  std::vector<Eigen::Vector2d> pts;
  for (int k = 0; k < d.sides(); ++k) {
    for (double r : {0.1, 0.45, 0.8, 0.97}) {
      for (double f : {0.2, 0.5, 0.9}) pts.push_back(r * ((1 - f) * d.vertex(k) + f * d.vertex(k + 1)));
    }
  }
  return pts;
}

TEST(NGonDomain, RejectsFewerThanThreeSides) { EXPECT_THROW(NGonDomain(2), std::invalid_argument); }

TEST(NGonDomain, BarycentricsArePartitionOfUnityAndPseudoAffine) {  // P2
  for (int n = 3; n <= 8; ++n) {
    const NGonDomain d(n);
    for (const Eigen::Vector2d& p : interiorGrid(d)) {
      const auto b = d.barycentric(p);
      double sum = 0.0;
      Eigen::Vector2d affine = Eigen::Vector2d::Zero();
      for (int k = 0; k < n; ++k) {
        sum += b[k].v;
        affine += b[k].v * d.vertex(k);
        EXPECT_GT(b[k].v, 0.0);
      }
      EXPECT_NEAR(sum, 1.0, 1e-14);
      EXPECT_LE((affine - p).norm(), 1e-13) << "N=" << n;
    }
  }
}

TEST(NGonDomain, BarycentricAtVertexIsKronecker) {
  for (int n = 3; n <= 8; ++n) {
    const NGonDomain d(n);
    for (int i = 0; i < n; ++i) {
      const auto b = d.barycentric(d.vertex(i));
      for (int k = 0; k < n; ++k) EXPECT_NEAR(b[k].v, k == i ? 1.0 : 0.0, 1e-14);
    }
  }
}

TEST(NGonDomain, UTildeIsUniformAlongItsEdgeAndZeroOneOnNeighbours) {  // Kuriyama 1996, secs. 2.4.2, 5.2.1
  for (int n = 3; n <= 8; ++n) {
    const NGonDomain d(n);
    for (int i = 0; i < n; ++i) {
      for (double s : {0.1, 0.37, 0.5, 0.81}) {
        const Eigen::Vector2d onEdge = (1 - s) * d.vertex(i) + s * d.vertex(i + 1);
        const auto b = d.barycentric(onEdge);
        EXPECT_NEAR(d.uTilde(i, b).v, s, 1e-13);
        EXPECT_NEAR(d.distance(i, b).v, 0.0, 1e-14);
        const Eigen::Vector2d onPrev = (1 - s) * d.vertex(i - 1) + s * d.vertex(i);
        EXPECT_NEAR(d.uTilde(i, d.barycentric(onPrev)).v, 0.0, 1e-13);
        const Eigen::Vector2d onNext = (1 - s) * d.vertex(i + 1) + s * d.vertex(i + 2);
        EXPECT_NEAR(d.uTilde(i, d.barycentric(onNext)).v, 1.0, 1e-13);
      }
    }
  }
}

TEST(NGonDomain, BlendIsPartitionOfUnityOneOnOwnEdgeZeroOnOthers) {  // P2, F2
  for (int n = 3; n <= 5; ++n) {
    const NGonDomain d(n);
    for (const Eigen::Vector2d& p : interiorGrid(d)) {
      const auto bl = d.blend(d.barycentric(p), 3);
      double sum = 0.0;
      for (const Jet& j : bl) sum += j.v;
      EXPECT_NEAR(sum, 1.0, 1e-14);
    }
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d onEdge = 0.6 * d.vertex(i) + 0.4 * d.vertex(i + 1);
      const auto bl = d.blend(d.barycentric(onEdge), 3);
      for (int k = 0; k < n; ++k) EXPECT_NEAR(bl[k].v, k == i ? 1.0 : 0.0, 1e-14);
    }
    const auto centre = d.blend(d.barycentric(Eigen::Vector2d::Zero()), 3);
    for (const Jet& j : centre) EXPECT_NEAR(j.v, 1.0 / n, 1e-14);
  }
}

TEST(NGonDomain, BlendIsRotationallySymmetric) {  // F2: B_{i+1}(R p) = B_i(p)
  for (int n = 3; n <= 5; ++n) {
    const NGonDomain d(n);
    const double th = 2 * std::numbers::pi / n;
    const Eigen::Matrix2d rot{{std::cos(th), -std::sin(th)}, {std::sin(th), std::cos(th)}};
    for (const Eigen::Vector2d& p : interiorGrid(d)) {
      const auto a = d.blend(d.barycentric(p), 3);
      const auto b = d.blend(d.barycentric(rot * p), 3);
      for (int i = 0; i < n; ++i) EXPECT_NEAR(b[(i + 1) % n].v, a[i].v, 1e-13);
    }
  }
}

TEST(NGonDomain, BlendAtVertexUsesHalfRule) {
  const NGonDomain d(5);
  const auto bl = d.blend(d.barycentric(d.vertex(2)), 3);
  EXPECT_DOUBLE_EQ(bl[2].v, 0.5);
  EXPECT_DOUBLE_EQ(bl[1].v, 0.5);
  EXPECT_DOUBLE_EQ(bl[0].v, 0.0);
}

TEST(NGonDomain, JetDerivativesMatchFiniteDifferences) {
  const NGonDomain d(5);
  const Eigen::Vector2d p(0.13, -0.21);
  const double h = 1e-6;
  for (int i = 0; i < 5; ++i) {
    auto f = [&](const Eigen::Vector2d& q) { return d.blend(d.barycentric(q), 3)[i]; };
    const Jet j = f(p);
    EXPECT_NEAR(j.x, (f(p + Eigen::Vector2d(h, 0)).v - f(p - Eigen::Vector2d(h, 0)).v) / (2 * h), 1e-7);
    EXPECT_NEAR(j.y, (f(p + Eigen::Vector2d(0, h)).v - f(p - Eigen::Vector2d(0, h)).v) / (2 * h), 1e-7);
    EXPECT_NEAR(j.xy, (f(p + Eigen::Vector2d(0, h)).x - f(p - Eigen::Vector2d(0, h)).x) / (2 * h), 1e-6);
    EXPECT_NEAR(j.yy, (f(p + Eigen::Vector2d(0, h)).y - f(p - Eigen::Vector2d(0, h)).y) / (2 * h), 1e-6);
  }
}

}  // namespace
}  // namespace ffdkit::geometry::curvenet
