#include "ffdkit/geometry/cardinal/sigma_blend.h"

#include <cmath>
#include <sstream>
#include <string>
#include <utility>

#include "ffdkit/geometry/cardinal/cardinal_error.h"
#include "ffdkit/geometry/cardinal/sigma_curve.h"
#include "ffdkit/geometry/cardinal/sigma_refinement.h"
#include "ffdkit/geometry/gauss_legendre.h"

namespace ffdkit::geometry::cardinal {
namespace {

std::vector<double> knotList(const SigmaKnots& k) {
  return std::vector<double>(k.knots().data(), k.knots().data() + k.last() + 1);
}

// Knots of `other` strictly inside this knot range (refinedKnots drops near-duplicates).
std::vector<double> interiorKnotsOf(const SigmaKnots& other, const SigmaKnots& self) {
  std::vector<double> out;
  for (double x : knotList(other)) {
    if (x > self.start() && x < self.end()) out.push_back(x);
  }
  return out;
}

// d2/dv2 of basis function `slot` (cardinal index 0..2 or auxiliary index -1..2) of the
// blend knots at v.
double basisSecondDerivative(const SigmaKnots& k, bool auxiliary, int slot, double v) {
  Eigen::MatrixX3d p = Eigen::MatrixX3d::Zero(k.pointCount(), 3);
  Eigen::MatrixX3d s = Eigen::MatrixX3d::Zero(k.shapeCount(), 3);
  if (auxiliary) {
    s(slot - k.shapeFirst(), 0) = 1.0;
  } else {
    p(slot, 0) = 1.0;
  }
  return SigmaCurve(k, p, s).evaluate(v, 2).x();
}

// Eq. (3.39): weights of (P_n, P_{n+2}, Pv_{n-1}, Pv_n, Pv_{n+1}, Pv_{n+2}) that minimise
// int ||q''||^2 over the middle point. q'' is quadratic per interval, so 3-point
// Gauss-Legendre per interval is exact (Kuriyama 1996, sec. 3.3.7).
std::array<double, 6> middleRowWeights(const SigmaKnots& blendKnots) {
  const GaussLegendreRule rule = gaussLegendreRule(3);
  const auto integral = [&](bool auxA, int a, bool auxB, int b) {
    double sum = 0.0;
    for (int interval = 0; interval < 2; ++interval) {
      const double lo = blendKnots.knot(interval), hi = blendKnots.knot(interval + 1);
      // Sample strictly inside the interval so that the right piece is used.
      sum += integrateGaussLegendre(rule, lo, hi, [&](double v) {
        return basisSecondDerivative(blendKnots, auxA, a, v) *
               basisSecondDerivative(blendKnots, auxB, b, v);
      });
    }
    return sum;
  };
  const double norm = integral(false, 1, false, 1);
  const std::array<std::pair<bool, int>, 6> known = {
      {{false, 0}, {false, 2}, {true, -1}, {true, 0}, {true, 1}, {true, 2}}};
  std::array<double, 6> w{};
  for (std::size_t k = 0; k < known.size(); ++k) {
    w[k] = -integral(known[k].first, known[k].second, false, 1) / norm;
  }
  return w;
}

}  // namespace

BlendResult blendSurfaces(const SigmaSurface& first, const SigmaSurface& second,
                          const BlendOptions& options) {
  first.validate();
  second.validate();
  if (first.knotsV.closed() || second.knotsV.closed()) {
    throw CardinalSplineError("blendSurfaces: both surfaces must be open in v (the blend joins "
                              "surface 1's v-end to surface 2's v-start)");
  }
  if (first.knotsU.closed() != second.knotsU.closed()) {
    throw CardinalSplineError("blendSurfaces: u closedness differs (surface 1 " +
                              std::string(first.knotsU.closed() ? "closed" : "open") +
                              ", surface 2 " + (second.knotsU.closed() ? "closed" : "open") + ")");
  }
  const double range = first.knotsU.end() - first.knotsU.start();
  const double tol = 1e-9 * range;
  if (std::abs(first.knotsU.start() - second.knotsU.start()) > tol ||
      std::abs(first.knotsU.end() - second.knotsU.end()) > tol) {
    std::ostringstream msg;
    msg << "blendSurfaces: u ranges must agree, got [" << first.knotsU.start() << ", "
        << first.knotsU.end() << "] and [" << second.knotsU.start() << ", "
        << second.knotsU.end() << "]";
    throw CardinalSplineError(msg.str());
  }
  for (double b : options.junctionBeta2) {
    if (!(b >= 0.0)) throw CardinalSplineError("blendSurfaces: junction beta2 must be >= 0");
  }

  std::vector<std::string> warnings;
  // Step 1: common u knots (refinement keeps both shapes, Kuriyama 1996, sec. 3.3.6).
  const SigmaSurface r1 = refine(first, interiorKnotsOf(second.knotsU, first.knotsU), {});
  const SigmaSurface r2 = refine(second, interiorKnotsOf(first.knotsU, second.knotsU), {});
  if (r1.knotsU.last() != r2.knotsU.last()) {
    throw CardinalSplineError("blendSurfaces: merging the u knot vectors failed (" +
                              std::to_string(r1.knotsU.last() + 1) + " vs " +
                              std::to_string(r2.knotsU.last() + 1) + " knots)");
  }
  for (int i = 0; i < r1.knotsU.beta2Values().size(); ++i) {
    if (r1.knotsU.beta2(i) != r2.knotsU.beta2(i)) {
      warnings.push_back("u-knot " + std::to_string(i) + " (u = " +
                                std::to_string(r1.knotsU.knot(i)) + "): beta2 " +
                                std::to_string(r1.knotsU.beta2(i)) + " (surface 1) vs " +
                                std::to_string(r2.knotsU.beta2(i)) +
                                " (surface 2); surface 1's value is used, surface 2 is not "
                                "reproduced exactly and the blend is G1 only there");
    }
  }
  const SigmaKnots& ku = r1.knotsU;

  // Step 2: concatenated v knots with a middle knot.
  const SigmaKnots& k1 = r1.knotsV;
  const SigmaKnots& k2 = r2.knotsV;
  const int n = k1.last();
  const int n2 = k2.last();
  const double gap0 = options.gapBefore.value_or(k1.delta(n - 1));
  const double gap1 = options.gapAfter.value_or(k2.delta(0));
  if (!(gap0 > 0.0) || !(gap1 > 0.0)) {
    throw CardinalSplineError("blendSurfaces: gap widths must be > 0, got " +
                              std::to_string(gap0) + " and " + std::to_string(gap1));
  }
  const int total = n + n2 + 2;  // last composite knot index
  Eigen::VectorXd tv(total + 1), bv(total + 1);
  for (int j = 0; j <= n; ++j) {
    tv[j] = k1.knot(j);
    bv[j] = k1.beta2(j);
  }
  tv[n + 1] = tv[n] + gap0;
  tv[n + 2] = tv[n + 1] + gap1;
  const double vOffset = tv[n + 2] - k2.start();
  for (int j = 1; j <= n2; ++j) {
    tv[n + 2 + j] = k2.knot(j) + vOffset;
    bv[n + 2 + j] = k2.beta2(j);
  }
  bv[n] = options.junctionBeta2[0];
  bv[n + 1] = options.junctionBeta2[1];
  bv[n + 2] = options.junctionBeta2[2];
  SigmaKnotsOptions kvOptions;
  kvOptions.phantomBefore = k1.delta(-1);
  kvOptions.phantomAfter = k2.delta(n2);
  const SigmaKnots kv(tv, bv, kvOptions);
  SigmaKnotsOptions blendOptions;
  blendOptions.phantomBefore = kv.delta(n - 1);
  blendOptions.phantomAfter = kv.delta(n + 2);
  const SigmaKnots kb(tv.segment(n, 3), bv.segment(n, 3), blendOptions);
  const std::array<double, 6> w = middleRowWeights(kb);

  // Steps 4-6, column by column: knot u-columns carry (P, Pv), shape u-columns (Pu, Puv).
  const auto composeColumn = [&](const Eigen::MatrixX3d& p1, const Eigen::MatrixX3d& s1,
                                 const Eigen::MatrixX3d& p2, const Eigen::MatrixX3d& s2,
                                 Eigen::MatrixX3d& p, Eigen::MatrixX3d& s) {
    const QuarticBezier b1 = SigmaCurve(k1, p1, s1).bezier(n - 1);
    const QuarticBezier b2 = SigmaCurve(k2, p2, s2).bezier(0);
    p.resize(kv.pointCount(), 3);
    s.resize(kv.shapeCount(), 3);
    // Composite shape index k sits in row k + 1.
    p.topRows(n + 1) = p1;
    s.topRows(n + 1) = s1.topRows(n + 1);  // shape -1..n-1
    p.bottomRows(n2 + 1) = p2;
    s.bottomRows(n2 + 1) = s2.bottomRows(n2 + 1);  // shape 0..n2 -> n+2..n+n2+2
    const Eigen::Vector3d pn = b1[4], svm = b1[2];
    const Eigen::Vector3d svn = (b1[3] - kv.C0(n) * pn - kv.Chat3(n - 1) * svm) / kv.Chat0(n);
    const Eigen::Vector3d pn2 = b2[0], svn2 = b2[2];
    const Eigen::Vector3d svn1 =
        (b2[1] - kv.C1(n + 2) * pn2 - kv.Chat1(n + 2) * svn2) / kv.Chat4(n + 1);
    p.row(n) = pn.transpose();
    p.row(n + 2) = pn2.transpose();
    s.row(n - 1 + 1) = svm.transpose();
    s.row(n + 1) = svn.transpose();
    s.row(n + 1 + 1) = svn1.transpose();
    s.row(n + 2 + 1) = svn2.transpose();
    p.row(n + 1) = (w[0] * pn + w[1] * pn2 + w[2] * svm + w[3] * svn + w[4] * svn1 + w[5] * svn2)
                       .transpose();
  };

  SigmaSurface c{ku, kv, {}, {}, {}, {}};
  c.P = PointGrid(ku.pointCount(), kv.pointCount());
  c.Pv = PointGrid(ku.pointCount(), kv.shapeCount());
  c.Pu = PointGrid(ku.shapeCount(), kv.pointCount());
  c.Puv = PointGrid(ku.shapeCount(), kv.shapeCount());
  const auto store = [](PointGrid& g, int row, const Eigen::MatrixX3d& m) {
    for (int j = 0; j < g.cols; ++j) g(row, j) = m.row(j).transpose();
  };
  Eigen::MatrixX3d p, s;
  for (int i = 0; i < ku.pointCount(); ++i) {
    composeColumn(r1.P.row(i), r1.Pv.row(i), r2.P.row(i), r2.Pv.row(i), p, s);
    store(c.P, i, p);
    store(c.Pv, i, s);
  }
  for (int i = 0; i < ku.shapeCount(); ++i) {
    composeColumn(r1.Pu.row(i), r1.Puv.row(i), r2.Pu.row(i), r2.Puv.row(i), p, s);
    store(c.Pu, i, p);
    store(c.Puv, i, s);
  }
  c.validate();

  // The blend alone: composite knot columns n..n+2 and shape columns n-1..n+2.
  SigmaSurface b{ku, kb, {}, {}, {}, {}};
  const auto slice = [](const PointGrid& g, int firstCol, int count) {
    PointGrid out(g.rows, count);
    for (int i = 0; i < g.rows; ++i)
      for (int j = 0; j < count; ++j) out(i, j) = g(i, firstCol + j);
    return out;
  };
  b.P = slice(c.P, n, 3);
  b.Pu = slice(c.Pu, n, 3);
  b.Pv = slice(c.Pv, n, 4);    // shape n-1 sits in column n
  b.Puv = slice(c.Puv, n, 4);
  b.validate();
  return BlendResult{std::move(b), std::move(c), vOffset, w, std::move(warnings)};
}

}  // namespace ffdkit::geometry::cardinal
