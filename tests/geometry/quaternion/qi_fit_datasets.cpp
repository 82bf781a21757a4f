#include "qi_fit_datasets.h"

#include <cmath>
#include <random>

#include "ffdkit/geometry/quaternion/unit_quaternion.h"

namespace ffdkit::geometry::quaternion::testdata {

void addUniformNoise(Eigen::MatrixX3d& points, double a, std::uint32_t seed, bool planar) {
  std::mt19937 gen(seed);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    for (int c = 0; c < (planar ? 2 : 3); ++c) {
      const double r = static_cast<double>(gen()) / 4294967296.0;
      points(i, c) += a * (2.0 * r - 1.0);
    }
  }
}

FitDataset sine(const std::vector<int>& breaks) {
  FitDataset d;
  d.points = Eigen::MatrixX3d::Zero(31, 3);
  for (int i = 0; i <= 30; ++i) {
    const double x = 2.0 * M_PI * i / 30.0;
    d.points.row(i) << 35.0 * x, 35.0 * std::sin(x), 0.0;
  }
  d.breaks = breaks;
  return d;
}

FitDataset sineNoisy() {
  FitDataset d = sine({0, 6, 15, 24, 30});
  addUniformNoise(d.points, 1.33706923, 12345, true);
  return d;
}

namespace {
FitDataset sampleChain(const QiChain& chain, int perSegment, double a, double b) {
  FitDataset d;
  const int m = chain.segmentCount();
  d.points.resize(m * perSegment + 1, 3);
  d.trueU.resize(m * perSegment + 1);
  for (int seg = 0; seg < m; ++seg) {
    Eigen::VectorXd x(perSegment + 1);
    for (int k = 0; k <= perSegment; ++k) {
      const double f = static_cast<double>(k) / perSegment;
      x[k] = a * f + b * f * f;
    }
    const Eigen::MatrixX3d p = chain.segment(seg).points(x);
    for (int k = 0; k <= perSegment; ++k) {
      d.points.row(seg * perSegment + k) = p.row(k);
      d.trueU[seg * perSegment + k] = seg + x[k];
    }
    d.breaks.push_back(seg * perSegment);
  }
  d.breaks.push_back(m * perSegment);
  return d;
}
}  // namespace

QiChain chain2dTruth() {
  QiChain c(Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity());
  c.appendSegment({{0, 0, 0.10}, {0, 0, 0.35}}, 100.0);
  c.appendSegment({{0, 0, 0.30}, {0, 0, -0.40}}, 120.0);
  c.appendSegment({{0, 0, -0.25}, {0, 0, 0.05}}, 80.0);
  return c;
}

FitDataset chain2d() { return sampleChain(chain2dTruth(), 10, 0.6, 0.4); }

FitDataset chain2dNoisy() {
  FitDataset d = chain2d();
  addUniformNoise(d.points, 1.5, 2024, true);
  return d;
}

QiChain chain3dTruth() {
  QiChain c(Eigen::Vector3d::Zero(), quaternionExp(Eigen::Vector3d(0, 0, 0.3)));
  c.appendSegment({{0.05, 0.10, 0.20}, {0.10, -0.05, 0.30}}, 100.0);
  c.appendSegment({{-0.10, 0.15, 0.25}, {0.05, 0.20, -0.30}}, 120.0);
  c.appendSegment({{0.15, -0.10, -0.20}, {-0.05, 0.05, 0.15}}, 80.0);
  return c;
}

FitDataset chain3d() { return sampleChain(chain3dTruth(), 23, 0.7, 0.3); }

FitDataset chain3dNoisy() {
  FitDataset d = chain3d();
  addUniformNoise(d.points, 1.5, 777, false);
  return d;
}

FitDataset helix() {
  FitDataset d;
  d.points.resize(70, 3);
  for (int i = 0; i < 70; ++i) {
    const double phi = 3.0 * M_PI * i / 69.0;
    d.points.row(i) << 30.0 * std::cos(phi), 30.0 * std::sin(phi), 8.0 * phi;
  }
  d.breaks = {0, 23, 46, 69};
  return d;
}

FitDataset spiral(int segments) {
  FitDataset d;
  d.points.resize(164, 3);
  for (int i = 0; i <= 163; ++i) {
    const double t = 3.0 * M_PI * i / 163.0;
    const double r = 50.0 - 3.0 * t;
    d.points.row(i) << r * std::cos(t), r * std::sin(t), 6.0 * t;
  }
  if (segments == 16) {
    d.breaks = {0, 10, 20, 31, 41, 51, 61, 71, 82, 92, 102, 112, 122, 132, 143, 153, 163};
  } else if (segments == 8) {
    d.breaks = {0, 20, 41, 61, 82, 102, 122, 143, 163};
  } else {
    d.breaks = {0, 27, 54, 82, 109, 136, 163};
  }
  return d;
}

FitDataset spiralNoisy(int segments) {
  FitDataset d = spiral(segments);
  addUniformNoise(d.points, 1.72066449, 164, false);
  return d;
}

}  // namespace ffdkit::geometry::quaternion::testdata
