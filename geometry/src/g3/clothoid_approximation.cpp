#include "ffdkit/geometry/g3/clothoid_approximation.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "ffdkit/geometry/g3/g3_error.h"
#include "span_quadrature.h"

namespace ffdkit::geometry::g3 {
namespace {

double segmentDistance2(const Eigen::Vector2d& q, const Eigen::MatrixX2d& line, Eigen::Index k) {
  const Eigen::Vector2d a = line.row(k).transpose();
  const Eigen::Vector2d d = line.row(k + 1).transpose() - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((q - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + t * d - q).squaredNorm();
}

// Distance from q to a densely sampled smooth polyline: the nearest vertex, then its two
// segments. Along a smooth curve the distance to q is unimodal around its minimum, so the
// nearest point of the polyline lies on a segment at the nearest vertex.
double pointToPolyline(const Eigen::Vector2d& q, const Eigen::MatrixX2d& line) {
  Eigen::Index k = 0;
  double best = (line.rowwise() - q.transpose()).rowwise().squaredNorm().minCoeff(&k);
  if (k > 0) best = std::min(best, segmentDistance2(q, line, k - 1));
  if (k + 1 < line.rows()) best = std::min(best, segmentDistance2(q, line, k));
  return std::sqrt(best);
}

double hausdorff(const Eigen::MatrixX2d& a, const Eigen::MatrixX2d& b) {
  double worst = 0.0;
  for (Eigen::Index k = 0; k < a.rows(); ++k) worst = std::max(worst, pointToPolyline(a.row(k).transpose(), b));
  for (Eigen::Index k = 0; k < b.rows(); ++k) worst = std::max(worst, pointToPolyline(b.row(k).transpose(), a));
  return worst;
}

struct SpanView {
  const QuadraticCurvatureSpline& curve;
  int span;
  Eigen::Vector4d bezier;
  Eigen::Vector3d kappa;
  double ds;

  double angle(double t) const { return detail::cubicBezier(bezier, t); }
  double curvature(double t) const {
    const double sigma = t * ds;
    return kappa[0] + sigma * (kappa[1] + sigma * kappa[2]);
  }
  Eigen::Vector2d point(double t) const {
    if (t <= 0.0) return curve.spanStarts().row(span).transpose();
    if (t >= 1.0) return curve.spanStarts().row(span + 1).transpose();
    const int panels = detail::panelCount(detail::controlPolygonTurning(bezier) * t, 1.0);
    return curve.spanStarts().row(span).transpose() +
           ds * detail::integrateTangent(detail::defaultRule(), [&](double u) { return angle(u); }, 0.0, t, panels);
  }
};

}  // namespace

Eigen::MatrixX2d sampleClothoidArcs(const std::vector<ClothoidArc>& arcs, int perArc) {
  if (perArc < 1) throw G3InputError("sampleClothoidArcs needs >= 1 sample per arc");
  Eigen::MatrixX2d out(static_cast<Eigen::Index>(arcs.size()) * perArc + 1, 2);
  Eigen::Index k = 0;
  const auto& rule = detail::defaultRule();
  for (const ClothoidArc& arc : arcs) {
    Eigen::Vector2d p = arc.start;
    const double step = arc.length / perArc;
    for (int j = 0; j < perArc; ++j, ++k) {
      if (j > 0) {
        const double a = (j - 1) * step, b = j * step;
        const double turning = std::abs(arc.curvature(a)) * step + 0.5 * std::abs(arc.sharpness) * step * step;
        p += detail::integrateTangent(rule, [&](double t) { return arc.angle(t); }, a, b,
                                      detail::panelCount(turning, 1.0));
      }
      out.row(k) = p.transpose();
    }
  }
  if (!arcs.empty()) out.row(k) = arcs.back().endPoint().transpose();
  else out.row(0).setZero();
  return out;
}

ClothoidApproximation approximateByClothoids(const QuadraticCurvatureSpline& curve,
                                             const ClothoidApproximationOptions& options) {
  if (options.subdivisionLevels < 1 || options.subdivisionLevels > 8) {
    std::ostringstream msg;
    msg << "approximateByClothoids: subdivisionLevels must be in 1..8, got " << options.subdivisionLevels;
    throw G3InputError(msg.str());
  }
  if (options.errorSamplesPerSpan < 8) {
    std::ostringstream msg;
    msg << "approximateByClothoids: errorSamplesPerSpan must be >= 8, got " << options.errorSamplesPerSpan;
    throw G3InputError(msg.str());
  }
  ClothoidApproximation out;
  const int n = curve.spanCount();
  out.spans.reserve(n);
  out.junctionFractions.reserve(n);
  for (int i = 0; i < n; ++i) {
    const SpanView view{curve, i, curve.bezierOrdinates().segment<4>(3 * i), curve.curvatureQuadratic(i),
                        curve.spanLength(i)};
    const Eigen::Vector4d& b = view.bezier;
    const double a1 = 3.0 * (b[1] - b[0]), a2 = 3.0 * (b[2] - 2.0 * b[1] + b[0]);
    const double a3 = b[3] - 3.0 * b[2] + 3.0 * b[1] - b[0];
    // On a clothoid span every split with sigma_0 + sigma_1 = length reproduces it and the 2x2
    // Jacobian is singular: take the symmetric split directly (Kuroda et al. 1997, sec. 6,
    // degenerate spans).
    const bool clothoidSpan = std::abs(a3) <= 1e-12 * (1.0 + std::abs(a1) + std::abs(a2));
    SpanApproximationError err;
    err.firstArc = static_cast<int>(out.arcs.size());

    auto fitPiece = [&](auto&& self, double ta, double tb, int level) -> void {
      BiClothoidEnds ends;
      ends.startPoint = view.point(ta);
      ends.endPoint = view.point(tb);
      ends.startAngle = view.angle(ta);
      ends.endAngle = view.angle(tb);
      ends.startCurvature = view.curvature(ta);
      ends.endCurvature = view.curvature(tb);
      const double length = (tb - ta) * view.ds;
      std::array<ClothoidArc, 2> arcs;
      double fraction = 0.5;
      if (clothoidSpan) {
        arcs = makeBiClothoid(ends, 0.5 * length, 0.5 * length);
      } else {
        const BiClothoidResult fit = fitBiClothoid(ends, length, options.fit);
        if (!fit.converged) err.converged = false;
        if (fit.arcs[0].length > 0.0 && fit.arcs[1].length > 0.0) {
          arcs = fit.arcs;
          fraction = arcs[0].length / (arcs[0].length + arcs[1].length);
        } else {
          arcs = makeBiClothoid(ends, 0.5 * length, 0.5 * length);
        }
      }
      if (level == 1) out.junctionFractions.push_back(fraction);
      if (level == options.subdivisionLevels) {
        out.arcs.push_back(arcs[0]);
        out.arcs.push_back(arcs[1]);
        return;
      }
      const double tm = ta + (tb - ta) * fraction;
      self(self, ta, tm, level + 1);
      self(self, tm, tb, level + 1);
    };
    fitPiece(fitPiece, 0.0, 1.0, 1);
    err.arcCount = static_cast<int>(out.arcs.size()) - err.firstArc;
    double total = 0.0;
    for (int k = err.firstArc; k < err.firstArc + err.arcCount; ++k) total += out.arcs[k].length;
    err.lengthDeviation = (total - view.ds) / view.ds;

    if (options.measureErrors) {
      const int m = options.errorSamplesPerSpan;
      Eigen::MatrixX2d original(m + 1, 2);
      Eigen::Vector2d p = view.point(0.0);
      const int panels = detail::panelCount(detail::controlPolygonTurning(b) / m, 1.0);
      for (int k = 0; k <= m; ++k) {
        if (k > 0) {
          p += view.ds * detail::integrateTangent(detail::defaultRule(), [&](double u) { return view.angle(u); },
                                                  static_cast<double>(k - 1) / m, static_cast<double>(k) / m, panels);
        }
        original.row(k) = p.transpose();
      }
      const std::vector<ClothoidArc> spanArcs(out.arcs.begin() + err.firstArc,
                                              out.arcs.begin() + err.firstArc + err.arcCount);
      const Eigen::MatrixX2d approx = sampleClothoidArcs(spanArcs, std::max(4, m / err.arcCount));
      err.hausdorff = hausdorff(original, approx);
      // Curvature at proportional arc length (Kuroda et al. 1997, sec. 6, Fig. 5).
      for (int k = 0; k <= m; ++k) {
        const double tau = static_cast<double>(k) / m;
        double sigma = tau * total;
        int a = 0;
        while (a + 1 < err.arcCount && sigma > spanArcs[a].length) sigma -= spanArcs[a++].length;
        sigma = std::min(sigma, spanArcs[a].length);
        err.maxCurvatureDeviation =
            std::max(err.maxCurvatureDeviation, std::abs(spanArcs[a].curvature(sigma) - view.curvature(tau)));
      }
    }
    if (std::abs(err.lengthDeviation) > 0.02) {
      std::ostringstream msg;
      msg << "span " << i << ": clothoid arcs differ in length from the span by " << 100.0 * err.lengthDeviation << " %";
      out.warnings.push_back(msg.str());
    }
    out.converged = out.converged && err.converged;
    out.maxHausdorff = std::max(out.maxHausdorff, err.hausdorff);
    out.maxCurvatureDeviation = std::max(out.maxCurvatureDeviation, err.maxCurvatureDeviation);
    out.spans.push_back(err);
  }
  return out;
}

}  // namespace ffdkit::geometry::g3
