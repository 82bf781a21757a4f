#include "ffdkit/geometry/quaternion/sphere_tangent_fit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "ffdkit/geometry/quaternion/quaternion_error.h"
#include "ffdkit/geometry/quaternion/tangent_integration.h"
#include "ffdkit/geometry/quaternion/unit_quaternion.h"

namespace ffdkit::geometry::quaternion {

Eigen::Vector3d polarPoint(double theta, double phi) {
  return {std::cos(theta) * std::cos(phi), std::sin(theta), std::cos(theta) * std::sin(phi)};
}

namespace {

// The maximum of f = 1/2 |a - b|^2 over unit a, b: returned for infeasible trials.
constexpr double kPenalty = 2.0;

// Great-arc point between e_x and v, with a fixed detour through e_y when v is antipodal to e_x.
Eigen::Vector3d arcPoint(const Eigen::Vector3d& v, double t) {
  if (angleBetween(Eigen::Vector3d::UnitX(), v) > M_PI - 1e-9) {
    return std::cos(M_PI * t) * Eigen::Vector3d::UnitX() + std::sin(M_PI * t) * Eigen::Vector3d::UnitY();
  }
  return slerpSphere(Eigen::Vector3d::UnitX(), v, t);
}

Eigen::Vector2d chartOf(const Eigen::Vector3d& p) {
  return {std::asin(std::clamp(p.y(), -1.0, 1.0)), std::atan2(p.z(), p.x())};
}

struct Canonical {
  Eigen::Quaterniond toCanonical;  // R with R V_a = e_x
  Eigen::Vector3d endPoint;        // R (P_c - P_a)
  Eigen::Vector3d endTangent;      // R V_c, unit
  Eigen::Vector3d direction;       // V_s = P_c / |P_c|
  std::optional<Eigen::Vector3d> secondControl;
};

std::vector<Eigen::Vector3d> controlsOf(const Canonical& c, const Eigen::Vector2d& x) {
  std::vector<Eigen::Vector3d> v = {Eigen::Vector3d::UnitX(), polarPoint(x[0], x[1])};
  if (c.secondControl) v.push_back(*c.secondControl);
  v.push_back(c.endTangent);
  return v;
}

// f(theta, phi) and the integrated end point at L = 1 (canonical frame), or the penalty.
double objective(const Canonical& c, const Eigen::Vector2d& x, SphereCurveKind kind, const TangentQuadrature& quad,
                 Eigen::Vector3d* endAtUnitLength = nullptr) {
  const std::vector<Eigen::Vector3d> v = controlsOf(c, x);
  for (std::size_t i = 1; i < v.size(); ++i) {
    if (angleBetween(v[i - 1], v[i]) > M_PI - 1e-9) return kPenalty;
  }
  const SphereBezierTangent path(v, kind);
  const Eigen::Vector3d pe =
      integrateGaussLegendrePanels([&path](double t) { return path.tangent(t); }, quad.order, quad.panels);
  if (!(pe.norm() > 1e-12) || !pe.allFinite()) return kPenalty;
  if (endAtUnitLength != nullptr) *endAtUnitLength = pe;
  return 0.5 * (pe.normalized() - c.direction).squaredNorm();
}

}  // namespace

SphereTangentFitResult fitSphereTangentSegment(const SphereTangentSegmentSpec& spec, const NelderMeadOptions& options) {
  if (spec.degree != 2 && spec.degree != 3) {
    std::ostringstream msg;
    msg << "fitSphereTangentSegment: expected degree 2 or 3 (one free control), got " << spec.degree;
    throw QuaternionCurveError(msg.str());
  }
  if (!(spec.startTangent.norm() > 0.0) || !(spec.endTangent.norm() > 0.0)) {
    std::ostringstream msg;
    msg << "fitSphereTangentSegment: expected non-zero end tangents, got (" << spec.startTangent.transpose()
        << ") and (" << spec.endTangent.transpose() << ")";
    throw QuaternionCurveError(msg.str());
  }
  const Eigen::Vector3d chord = spec.endPoint - spec.startPoint;
  if (!(chord.norm() > 1e-12 * std::max(1.0, spec.startPoint.norm()))) {
    std::ostringstream msg;
    msg << "fitSphereTangentSegment: expected distinct end points, got P_a = P_c = (" << spec.startPoint.transpose()
        << ")";
    throw QuaternionCurveError(msg.str());
  }
  // Canonical frame: P_a = 0, V_a = e_x (Sphere-tangent report, sec. 5; the twist the paper leaves
  // free is fixed by FromTwoVectors).
  Canonical c;
  c.toCanonical = Eigen::Quaterniond::FromTwoVectors(spec.startTangent.normalized(), Eigen::Vector3d::UnitX());
  c.endPoint = c.toCanonical * chord;
  c.endTangent = (c.toCanonical * spec.endTangent).normalized();
  c.direction = c.endPoint.normalized();
  Eigen::Vector2d x0 = chartOf(arcPoint(c.endTangent, 0.5));
  if (spec.degree == 3) {
    c.secondControl = spec.fixedSecondControl ? (c.toCanonical * *spec.fixedSecondControl).normalized()
                                              : arcPoint(c.endTangent, 2.0 / 3.0);
    x0 = chartOf(arcPoint(c.endTangent, 1.0 / 3.0));
  }
  if (options.initialThetaPhi) x0 = *options.initialThetaPhi;

  // Nelder-Mead, coefficients 1 / 2 / 0.5 / 0.5 (Sphere-tangent report, sec. 5), from one or
  // several starts (Sphere-tangent report, sec. 5); the first start that solves the problem wins,
  // else the lowest f.
  SphereTangentFitResult result;
  const auto f = [&](const Eigen::Vector2d& x) {
    ++result.evaluations;
    return objective(c, x, spec.kind, options.quadrature);
  };
  bool stalled = false;
  const auto simplex = [&](const Eigen::Vector2d& start, Eigen::Vector2d& xBest) {
    std::array<Eigen::Vector2d, 3> xs = {start, start + Eigen::Vector2d(options.initialStep, 0.0),
                                         start + Eigen::Vector2d(0.0, options.initialStep)};
    std::array<double, 3> fs{};
    for (int i = 0; i < 3; ++i) fs[i] = f(xs[i]);
    double bestSoFar = *std::min_element(fs.begin(), fs.end());
    int iterations = 0, lastImprovement = 0;
    stalled = false;
    while (true) {
      std::array<int, 3> order = {0, 1, 2};
      std::sort(order.begin(), order.end(), [&](int i, int j) { return fs[i] < fs[j]; });
      const Eigen::Vector2d best = xs[order[0]], mid = xs[order[1]], worst = xs[order[2]];
      const double fb = fs[order[0]], fm = fs[order[1]], fw = fs[order[2]];
      const double diameter = std::max({(best - mid).norm(), (best - worst).norm(), (mid - worst).norm()});
      if ((fw - fb <= options.functionTolerance && diameter <= options.simplexTolerance) ||
          iterations >= options.maxIterations) {
        break;
      }
      if (fb < bestSoFar) {
        bestSoFar = fb;
        lastImprovement = iterations;
      } else if (iterations - lastImprovement >= options.stallIterations) {
        // Pinned against the infeasible (antipodal) boundary or a non-zero minimum: no progress left.
        stalled = true;
        break;
      }
      ++iterations;
      ++result.iterations;
      const Eigen::Vector2d centroid = 0.5 * (best + mid);
      const Eigen::Vector2d xr = centroid + (centroid - worst);
      const double fr = f(xr);
      if (fr < fb) {
        const Eigen::Vector2d xe = centroid + 2.0 * (xr - centroid);
        const double fe = f(xe);
        xs[order[2]] = fe < fr ? xe : xr;
        fs[order[2]] = std::min(fe, fr);
      } else if (fr < fm) {
        xs[order[2]] = xr;
        fs[order[2]] = fr;
      } else {
        const bool outside = fr < fw;
        const Eigen::Vector2d xc = outside ? Eigen::Vector2d(centroid + 0.5 * (xr - centroid))
                                           : Eigen::Vector2d(centroid + 0.5 * (worst - centroid));
        const double fc = f(xc);
        if ((outside && fc <= fr) || (!outside && fc < fw)) {
          xs[order[2]] = xc;
          fs[order[2]] = fc;
        } else {
          for (int k : {order[1], order[2]}) {
            xs[k] = best + 0.5 * (xs[k] - best);
            fs[k] = f(xs[k]);
          }
        }
      }
    }
    const int ib = static_cast<int>(std::min_element(fs.begin(), fs.end()) - fs.begin());
    xBest = xs[ib];
    return fs[ib];
  };
  // Further starts: other points of the great arc V_a -> V_c, then +-0.5 rad chart offsets.
  std::vector<Eigen::Vector2d> starts = {x0};
  for (double t : {0.25, 0.75}) starts.push_back(chartOf(arcPoint(c.endTangent, t)));
  for (const Eigen::Vector2d& d : {Eigen::Vector2d(0.5, 0.0), Eigen::Vector2d(-0.5, 0.0), Eigen::Vector2d(0.0, 0.5),
                                   Eigen::Vector2d(0.0, -0.5)}) {
    starts.push_back(x0 + d);
  }
  const int startCount = std::clamp(options.multiStarts, 1, static_cast<int>(starts.size()));
  double bestF = INFINITY;
  for (int sIdx = 0; sIdx < startCount; ++sIdx) {
    Eigen::Vector2d x;
    const double fx = simplex(starts[sIdx], x);
    if (fx < bestF) {
      bestF = fx;
      result.thetaPhi = x;
    }
    if (bestF <= options.successThreshold) break;
  }
  result.objective = bestF;
  const std::vector<Eigen::Vector3d> canonical = controlsOf(c, result.thetaPhi);
  for (const auto& v : canonical) result.controlsWorld.push_back(c.toCanonical.conjugate() * v);
  Eigen::Vector3d pe = Eigen::Vector3d::Zero();
  const double fBest = objective(c, result.thetaPhi, spec.kind, options.quadrature, &pe);
  if (fBest >= kPenalty || !(fBest <= options.successThreshold)) {
    std::ostringstream msg;
    msg << "no control direction aligns the end point: f = " << fBest << " > " << options.successThreshold << " after "
        << result.iterations << " simplex iterations from " << startCount << " start(s)"
        << (stalled ? " (stalled)" : "")
        << (fBest >= kPenalty ? " (the simplex was pulled to antipodal controls)" : "");
    result.message = msg.str();
    return result;
  }
  result.length = c.endPoint.norm() / pe.norm();
  TangentIntegralCurve curve(SphereBezierTangent(result.controlsWorld, spec.kind), result.length, spec.startPoint,
                             options.quadrature);
  result.endPositionError = (curve.endPoint() - spec.endPoint).norm();
  result.endTangentAngle = angleBetween(curve.tangent(result.length), spec.endTangent);
  result.curve = std::move(curve);
  result.converged = true;
  return result;
}

}  // namespace ffdkit::geometry::quaternion
