// plotCurvatureToPng on profiles built here with known curvature and torsion.
#include <gtest/gtest.h>

#include <numbers>

#include "cli_runner.h"
#include "ffdkit/render/curve_plot.h"
#include "png_image.h"

namespace ffdkit::app {
namespace {

using cli::test::PngImage;
using cli::test::TempDir;
using cli::test::blue;
using cli::test::countPixels;
using cli::test::orange;

/// A helix of radius r and pitch 2 pi c: curvature r / (r^2 + c^2), torsion c / (r^2 + c^2).
scenes::CurvatureProfile helix(double r, double c, int samples) {
  scenes::CurvatureProfile p;
  const double speed = std::sqrt(r * r + c * c);
  p.arcLength = Eigen::VectorXd::LinSpaced(samples, 0.0, 4.0 * std::numbers::pi * speed);
  p.curvature = Eigen::VectorXd::Constant(samples, r / (r * r + c * c));
  p.torsion = Eigen::VectorXd::Constant(samples, c / (r * r + c * c));
  p.points.resize(samples, 3);
  p.normals.resize(samples, 3);
  for (int i = 0; i < samples; ++i) {
    const double t = p.arcLength[i] / speed;
    p.points.row(i) << r * std::cos(t), r * std::sin(t), c * t;
    p.normals.row(i) << -std::cos(t), -std::sin(t), 0.0;
  }
  return p;
}

/// A clothoid's profile: curvature grows linearly with arc length; planar, so no torsion.
scenes::CurvatureProfile clothoid(int samples) {
  scenes::CurvatureProfile p;
  p.arcLength = Eigen::VectorXd::LinSpaced(samples, 0.0, 2.0);
  p.curvature = 1.5 * p.arcLength;
  return p;
}

TEST(CurvePlot, DrawsCurvatureAndTorsionOfASpaceCurve) {
  TempDir dir;
  plotCurvatureToPng(helix(1.0, 0.3, 200), dir / "helix.png", {.width = 400, .height = 300, .title = "helix"});
  const PngImage image = cli::test::readPng(dir / "helix.png");
  ASSERT_EQ(image.width, 400);
  ASSERT_EQ(image.height, 300);
  EXPECT_GT(countPixels(image, orange), 100);  // the curvature line
  EXPECT_GT(countPixels(image, blue), 100);    // the torsion line
}

TEST(CurvePlot, APlanarCurveHasNoTorsionLine) {
  TempDir dir;
  plotCurvatureToPng(clothoid(100), dir / "clothoid.png", {.width = 400, .height = 300, .title = ""});
  const PngImage image = cli::test::readPng(dir / "clothoid.png");
  EXPECT_GT(countPixels(image, orange), 100);
  EXPECT_LT(countPixels(image, blue), 10);
}

TEST(CurvePlot, RejectsAMalformedProfileAndWritesNothing) {
  TempDir dir;
  scenes::CurvatureProfile p = clothoid(10);
  p.curvature.resize(9);
  EXPECT_THROW(plotCurvatureToPng(p, dir / "a.png"), std::invalid_argument);
  p = clothoid(10);
  p.arcLength[3] = -1.0;
  EXPECT_THROW(plotCurvatureToPng(p, dir / "a.png"), std::invalid_argument);
  p = clothoid(10);
  p.torsion = Eigen::VectorXd::Zero(4);
  EXPECT_THROW(plotCurvatureToPng(p, dir / "a.png"), std::invalid_argument);
  EXPECT_THROW(plotCurvatureToPng(clothoid(1), dir / "a.png"), std::invalid_argument);
  EXPECT_THROW(plotCurvatureToPng(clothoid(10), dir / "a.png", {.width = 0, .height = 300, .title = ""}), std::invalid_argument);
  EXPECT_TRUE(dir.entries().empty());
}

}  // namespace
}  // namespace ffdkit::app
