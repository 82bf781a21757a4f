#include "ffdkit/widgets/ray.h"

#include <gtest/gtest.h>

namespace ffdkit::widgets {
namespace {

TEST(Ray, ClosestApproachToASegment) {
  const Ray ray{{0.5, 0.2, 3.0}, {0, 0, -2}};
  auto h = closestRaySegment(ray, {0, 0, 0}, {1, 0, 0});
  ASSERT_TRUE(h);
  EXPECT_NEAR(h->s, 0.5, 1e-15);
  EXPECT_NEAR(h->t, 3.0, 1e-15);
  EXPECT_NEAR(h->distance, 0.2, 1e-15);
}

TEST(Ray, LineParameterAndParallelRays) {
  const Ray ray{{0.3, -5.0, 1.0}, {0, 1, 0}};
  EXPECT_NEAR(*closestLineParameter(ray, {0, 0, 0}, {1, 0, 0}), 0.3, 1e-15);
  EXPECT_FALSE(closestLineParameter(ray, {0, 0, 0}, {0, 1, 0}).has_value());
}

TEST(Ray, PlaneAndTriangle) {
  const Ray ray{{0.2, 0.2, 1.0}, {0, 0, -1}};
  EXPECT_NEAR(*intersectPlane(ray, {0, 0, 0}, {0, 0, 1}), 1.0, 1e-15);
  EXPECT_FALSE(intersectPlane(ray, {0, 0, 2}, {0, 0, 1}).has_value());  // behind
  EXPECT_NEAR(*intersectTriangle(ray, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}), 1.0, 1e-15);
  EXPECT_FALSE(intersectTriangle(Ray{{0.8, 0.8, 1}, {0, 0, -1}}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}).has_value());
}

}  // namespace
}  // namespace ffdkit::widgets
