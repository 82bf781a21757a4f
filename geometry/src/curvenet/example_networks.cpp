#include "ffdkit/geometry/curvenet/example_networks.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace ffdkit::geometry::curvenet {
namespace {

CurveDescription polyline(std::string name, Eigen::MatrixX3d points, bool closed) {
  CurveDescription c;
  c.name = std::move(name);
  c.points = std::move(points);
  c.closed = closed;
  return c;
}

template <class F>
Eigen::MatrixX3d sampleLifted(int count, double a, double b, F&& xy) {
  Eigen::MatrixX3d p(count, 3);
  for (int k = 0; k < count; ++k) {
    const double s = a + (b - a) * k / (count - 1);
    const Eigen::Vector2d q = xy(s);
    p.row(k) << q.x(), q.y(), prototypeHeight(q.x(), q.y());
  }
  return p;
}

Eigen::MatrixX3d circle(int count, const Eigen::Vector3d& e0, const Eigen::Vector3d& e1) {
  Eigen::MatrixX3d p(count, 3);
  for (int k = 0; k < count; ++k) {
    const double th = 2.0 * std::numbers::pi * k / count;
    p.row(k) = (std::cos(th) * e0 + std::sin(th) * e1).transpose();
  }
  return p;
}

}  // namespace

double prototypeHeight(double x, double y) {
  return 0.3 * x * x - 0.2 * x * y + 0.25 * y * y + 0.1 * x * x * x + 0.05 * y * y * y +
         0.2 * x * x * y - 0.15 * x * y * y + 0.1 * std::sin(2.0 * x) * std::cos(1.5 * y);
}

CurveNetworkDescription sphereOctantNetwork() {
  const Eigen::Vector3d ex = Eigen::Vector3d::UnitX(), ey = Eigen::Vector3d::UnitY(),
                        ez = Eigen::Vector3d::UnitZ();
  CurveNetworkDescription d;
  d.curves.push_back(polyline("z=0", circle(8, ex, ey), true));
  d.curves.push_back(polyline("x=0", circle(8, ey, ez), true));
  d.curves.push_back(polyline("y=0", circle(8, ez, ex), true));
  return d;
}

CurveNetworkDescription meridianNetwork() {
  CurveNetworkDescription d;
  for (int k = 0; k < 3; ++k) {
    const double phi = k * std::numbers::pi / 3.0;
    d.curves.push_back(polyline("meridian " + std::to_string(60 * k),
                                circle(12, Eigen::Vector3d(std::cos(phi), std::sin(phi), 0.0),
                                       Eigen::Vector3d::UnitZ()),
                                true));
  }
  d.curves.push_back(polyline("equator", circle(12, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()), true));
  return d;
}

CurveNetworkDescription heightGridNetwork(int n, int pointsPerCurve) {
  if (n < 2) throw std::invalid_argument("height grid needs >= 2 curves per direction, got " + std::to_string(n));
  const int points = pointsPerCurve > 0 ? pointsPerCurve : 2 * n + 3;
  if (points < 4) throw std::invalid_argument("height grid needs >= 4 points per curve, got " + std::to_string(points));
  CurveNetworkDescription d;
  const double lo = -0.25, hi = 2.25;
  for (int i = 0; i < n; ++i) {
    const double c = 2.0 * i / (n - 1);
    d.curves.push_back(polyline("x=" + std::to_string(c),
                                sampleLifted(points, lo, hi, [&](double s) { return Eigen::Vector2d(c, s); }),
                                false));
    d.curves.push_back(polyline("y=" + std::to_string(c),
                                sampleLifted(points, lo, hi, [&](double s) { return Eigen::Vector2d(s, c); }),
                                false));
  }
  return d;
}

CurveNetworkDescription lensNetwork() {
  CurveNetworkDescription d;
  d.curves.push_back(polyline("upper parabola",
                              sampleLifted(14, -1.3, 1.3, [](double x) { return Eigen::Vector2d(x, 1.0 - x * x); }),
                              false));
  d.curves.push_back(polyline("lower parabola",
                              sampleLifted(14, -1.3, 1.3, [](double x) { return Eigen::Vector2d(x, x * x - 1.0); }),
                              false));
  d.curves.push_back(polyline("x=-0.5",
                              sampleLifted(6, 0.75, 1.8, [](double y) { return Eigen::Vector2d(-0.5, y); }),
                              false));
  d.curves.push_back(polyline("x=0.5",
                              sampleLifted(6, 0.75, 1.8, [](double y) { return Eigen::Vector2d(0.5, y); }),
                              false));
  d.curves.push_back(polyline("y=1.5",
                              sampleLifted(8, -0.8, 0.8, [](double x) { return Eigen::Vector2d(x, 1.5); }),
                              false));
  return d;
}

CurveNetworkDescription tJunctionNetwork() {
  CurveNetworkDescription d;
  for (double y : {-2.0, 0.0, 2.0}) {
    d.curves.push_back(polyline("y=" + std::to_string(y),
                                sampleLifted(11, -0.3, 2.3, [&](double x) { return Eigen::Vector2d(x, y); }),
                                false));
  }
  for (double x : {0.0, 2.0}) {
    d.curves.push_back(polyline("x=" + std::to_string(x),
                                sampleLifted(15, -2.3, 2.3, [&](double y) { return Eigen::Vector2d(x, y); }),
                                false));
  }
  d.curves.push_back(polyline("stem x=0.7",
                              sampleLifted(8, 0.0, 2.3, [](double y) { return Eigen::Vector2d(0.7, y); }),
                              false));
  return d;
}

CurveNetworkDescription translationalNetwork() {
  auto a = [](double u) { return Eigen::Vector3d(u, 0.0, 0.3 * u * u - 0.1 * u * u * u); };
  auto b = [](double v) { return Eigen::Vector3d(0.0, v, 0.2 * std::sin(1.5 * v)); };
  const double uMax = 2.0, vMax = 1.5;
  auto samples = [](auto&& f, double lo, double step, int count, const Eigen::Vector3d& offset) {
    Eigen::MatrixX3d p(count, 3);
    for (int k = 0; k < count; ++k) p.row(k) = (f(lo + step * k) + offset).transpose();
    return p;
  };
  CurveNetworkDescription d;
  // Samples at multiples of 0.25 so that the corners are interpolated points of both curves.
  d.curves.push_back(polyline("A+B(0)", samples(a, -0.5, 0.25, 13, b(0.0)), false));
  d.curves.push_back(polyline("A+B(1.5)", samples(a, -0.5, 0.25, 13, b(vMax)), false));
  d.curves.push_back(polyline("B+A(0)", samples(b, -0.5, 0.25, 11, a(0.0)), false));
  d.curves.push_back(polyline("B+A(2)", samples(b, -0.5, 0.25, 11, a(uMax)), false));
  return d;
}

std::vector<std::string> exampleNetworkNames() {
  return {"sphere-octants", "meridians", "height-grid", "lens", "t-junction", "translational"};
}

CurveNetworkDescription exampleNetwork(const std::string& name) {
  if (name == "sphere-octants") return sphereOctantNetwork();
  if (name == "meridians") return meridianNetwork();
  if (name == "height-grid") return heightGridNetwork(4);
  if (name == "lens") return lensNetwork();
  if (name == "t-junction") return tJunctionNetwork();
  if (name == "translational") return translationalNetwork();
  std::string known;
  for (const std::string& n : exampleNetworkNames()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown example network '" + name + "' (known: " + known + ")");
}

}  // namespace ffdkit::geometry::curvenet
