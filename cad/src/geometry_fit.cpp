#include "geometry_fit.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/QR>
#include <Precision.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array2OfPnt.hxx>

#include "ffdkit/ffd/bspline_basis.h"

namespace ffdkit::cad {

namespace {

constexpr int kMaxRounds = 6;
constexpr int kMaxSpans = 96;
constexpr int kMinSpans = 4;

/// The breakpoints of one direction of the fit, ends included, and the continuity kept at each
/// (C^k; the ends' entries are unused).
struct Breaks {
  std::vector<double> at;
  std::vector<int> continuity;
  int spans() const { return static_cast<int>(at.size()) - 1; }
};

Breaks initialBreaks(const TColStd_Array1OfReal& knots, const TColStd_Array1OfInteger& mults, int degree, double lo,
                     double hi, const std::vector<double>& kinks) {
  std::vector<std::pair<double, int>> interior;
  const double eps = 1e-9 * (hi - lo);
  for (Standard_Integer i = knots.Lower(); i <= knots.Upper(); ++i)
    if (knots(i) > lo + eps && knots(i) < hi - eps) interior.emplace_back(knots(i), std::max(0, degree - mults(i)));
  for (double k : kinks)
    if (k > lo + eps && k < hi - eps) interior.emplace_back(k, 0);
  std::sort(interior.begin(), interior.end());
  Breaks b;
  b.at.push_back(lo);
  b.continuity.push_back(0);
  for (const auto& [at, continuity] : interior) {
    if (at - b.at.back() <= eps) {
      b.continuity.back() = std::min(b.continuity.back(), continuity);
      continue;
    }
    b.at.push_back(at);
    b.continuity.push_back(continuity);
  }
  if (hi - b.at.back() <= eps) {
    b.at.pop_back();
    b.continuity.pop_back();
  }
  b.at.push_back(hi);
  b.continuity.push_back(0);
  while (b.spans() < kMinSpans) {
    Breaks finer;
    for (int s = 0; s < b.spans(); ++s) {
      finer.at.push_back(b.at[s]);
      finer.continuity.push_back(b.continuity[s]);
      finer.at.push_back(0.5 * (b.at[s] + b.at[s + 1]));
      finer.continuity.push_back(1000);  // smooth: a simple knot
    }
    finer.at.push_back(b.at.back());
    finer.continuity.push_back(0);
    b = finer;
  }
  return b;
}

/// Halves the marked spans (at most up to kMaxSpans spans); false when none was halved.
bool refine(Breaks& b, const std::vector<char>& marked) {
  Breaks finer;
  bool changed = false;
  int budget = kMaxSpans - b.spans();
  for (int s = 0; s < b.spans(); ++s) {
    finer.at.push_back(b.at[s]);
    finer.continuity.push_back(b.continuity[s]);
    if (marked[s] && budget > 0) {
      finer.at.push_back(0.5 * (b.at[s] + b.at[s + 1]));
      finer.continuity.push_back(1000);
      changed = true;
      --budget;
    }
  }
  finer.at.push_back(b.at.back());
  finer.continuity.push_back(0);
  b = finer;
  return changed;
}

/// The clamped knot vector of degree q over the breaks: interior multiplicity q - min(k, q - 1).
std::vector<double> flatKnots(const Breaks& b, int q) {
  std::vector<double> flat(q + 1, b.at.front());
  for (int i = 1; i + 1 < static_cast<int>(b.at.size()); ++i)
    flat.insert(flat.end(), q - std::min(b.continuity[i], q - 1), b.at[i]);
  flat.insert(flat.end(), q + 1, b.at.back());
  return flat;
}

/// Row r: the values of the B-spline basis functions of `flat` (degree q) at ts[r] (The NURBS
/// Book, A2.1 and A2.2).
Eigen::MatrixXd basisMatrix(const std::vector<double>& flat, int q, const std::vector<double>& ts) {
  const int n = static_cast<int>(flat.size()) - q - 1;
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(ts.size()), n);
  std::vector<double> values(q + 1);
  for (std::size_t r = 0; r < ts.size(); ++r) {
    const double t = ts[r];
    int span = n - 1;
    if (t < flat[n]) span = static_cast<int>(std::upper_bound(flat.begin() + q, flat.begin() + n, t) - flat.begin()) - 1;
    span = std::clamp(span, q, n - 1);
    ffd::bsplineBasisOnSpan(flat.data(), span, q, t, values.data(), nullptr);
    for (int k = 0; k <= q; ++k) m(static_cast<Eigen::Index>(r), span - q + k) = values[k];
  }
  return m;
}

/// The fit's sample parameters (q + 2 per span, inside it) and check parameters (between and
/// around them, the span ends included) with the span of each check parameter.
void parameters(const Breaks& b, int q, std::vector<double>& samples, std::vector<double>& checks, std::vector<int>& spanOf) {
  const int m = q + 2;
  samples.clear();
  checks.clear();
  spanOf.clear();
  for (int s = 0; s < b.spans(); ++s) {
    const double lo = b.at[s], hi = b.at[s + 1];
    for (int j = 0; j < m; ++j) {
      samples.push_back(lo + (hi - lo) * (j + 0.5) / m);
      checks.push_back(lo + (hi - lo) * double(j) / m);
      spanOf.push_back(s);
    }
  }
  checks.push_back(b.at.back());
  spanOf.push_back(b.spans() - 1);
}

/// The distinct knots and their multiplicities of a flat knot vector, as OpenCASCADE takes them.
struct KnotArrays {
  TColStd_Array1OfReal knots;
  TColStd_Array1OfInteger mults;
};

KnotArrays knotArrays(const std::vector<double>& flat) {
  std::vector<double> distinct;
  std::vector<int> count;
  for (double k : flat) {
    if (distinct.empty() || k != distinct.back()) {
      distinct.push_back(k);
      count.push_back(1);
    } else {
      ++count.back();
    }
  }
  const auto n = static_cast<Standard_Integer>(distinct.size());
  KnotArrays arrays{TColStd_Array1OfReal(1, n), TColStd_Array1OfInteger(1, n)};
  for (Standard_Integer i = 1; i <= n; ++i) {
    arrays.knots(i) = distinct[i - 1];
    arrays.mults(i) = count[i - 1];
  }
  return arrays;
}

/// What the fit keeps of the original's shape on the rectangle.
struct FitShape {
  bool closedU = false, closedV = false;  ///< the sides u = u0 and u = u1 (v = v0, v1) coincide
  bool pointAtU0 = false, pointAtU1 = false, pointAtV0 = false, pointAtV1 = false;  ///< a side is one point
};

FitShape shapeOf(const Handle(Geom_BSplineSurface)& surface, double u0, double u1, double v0, double v1) {
  Standard_Real su0, su1, sv0, sv1;
  surface->Bounds(su0, su1, sv0, sv1);
  const double eps = 1e-9;
  const bool wholeU = std::abs(u0 - su0) <= eps * (su1 - su0) && std::abs(u1 - su1) <= eps * (su1 - su0);
  const bool wholeV = std::abs(v0 - sv0) <= eps * (sv1 - sv0) && std::abs(v1 - sv1) <= eps * (sv1 - sv0);
  FitShape shape;
  shape.closedU = wholeU && surface->IsUClosed();
  shape.closedV = wholeV && surface->IsVClosed();
  auto collapsed = [&](bool alongU, double at) {
    const gp_Pnt first = alongU ? surface->Value(at, v0) : surface->Value(u0, at);
    for (int i = 1; i <= 16; ++i) {
      const gp_Pnt p = alongU ? surface->Value(at, v0 + (v1 - v0) * i / 16) : surface->Value(u0 + (u1 - u0) * i / 16, at);
      if (p.Distance(first) > Precision::Confusion()) return false;
    }
    return true;
  };
  shape.pointAtU0 = collapsed(true, u0);
  shape.pointAtU1 = collapsed(true, u1);
  shape.pointAtV0 = collapsed(false, v0);
  shape.pointAtV1 = collapsed(false, v1);
  return shape;
}

}  // namespace

SurfaceFit fitSurface(const FfdMap& map, const Handle(Geom_BSplineSurface)& surface, double u0, double u1, double v0,
                      double v1, int degreeU, int degreeV, double tolerance, bool extend, const std::vector<double>& kinksU,
                      const std::vector<double>& kinksV) {
  const FitShape shape = shapeOf(surface, u0, u1, v0, v1);
  TColStd_Array1OfReal uk(1, surface->NbUKnots()), vk(1, surface->NbVKnots());
  TColStd_Array1OfInteger um(1, surface->NbUKnots()), vm(1, surface->NbVKnots());
  surface->UKnots(uk);
  surface->VKnots(vk);
  surface->UMultiplicities(um);
  surface->VMultiplicities(vm);
  Breaks bu = initialBreaks(uk, um, surface->UDegree(), u0, u1, kinksU);
  Breaks bv = initialBreaks(vk, vm, surface->VDegree(), v0, v1, kinksV);
  SurfaceFit fit;
  auto ffdOfGrid = [&](const std::vector<double>& us, const std::vector<double>& vs) {
    Eigen::MatrixX3d world(static_cast<Eigen::Index>(us.size() * vs.size()), 3);
    Eigen::Index row = 0;
    for (double v : vs)
      for (double u : us) {
        const gp_Pnt p = surface->Value(u, v);
        world.row(row++) << p.X(), p.Y(), p.Z();
      }
    return map.points(world, extend);  // row i + |us| j
  };
  for (int round = 0;; ++round) {
    std::vector<double> su, sv, cu, cv;
    std::vector<int> spanU, spanV;
    parameters(bu, degreeU, su, cu, spanU);
    parameters(bv, degreeV, sv, cv, spanV);
    const std::vector<double> fu = flatKnots(bu, degreeU), fv = flatKnots(bv, degreeV);
    const Eigen::MatrixXd nu = basisMatrix(fu, degreeU, su), nv = basisMatrix(fv, degreeV, sv);
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qrU(nu), qrV(nv);
    const Eigen::MatrixX3d target = ffdOfGrid(su, sv);
    Eigen::MatrixXd poles[3];
    for (int c = 0; c < 3; ++c) {
      const Eigen::MatrixXd z = Eigen::Map<const Eigen::MatrixXd>(target.col(c).data(), su.size(), sv.size());
      const Eigen::MatrixXd x = qrU.solve(z);                      // nu x |sv|
      poles[c] = qrV.solve(x.transpose()).transpose();             // nu x nv
    }
    // What the original is exactly, the fit is too: closed where it closes on itself (a seam joins
    // the two sides), a point where a side collapses to one (a pole of a sphere).
    for (int c = 0; c < 3; ++c) {
      Eigen::MatrixXd& P = poles[c];
      if (shape.closedU) P.row(0) = P.row(P.rows() - 1) = 0.5 * (P.row(0) + P.row(P.rows() - 1));
      if (shape.closedV) P.col(0) = P.col(P.cols() - 1) = 0.5 * (P.col(0) + P.col(P.cols() - 1));
      if (shape.pointAtU0) P.row(0).setConstant(P.row(0).mean());
      if (shape.pointAtU1) P.row(P.rows() - 1).setConstant(P.row(P.rows() - 1).mean());
      if (shape.pointAtV0) P.col(0).setConstant(P.col(0).mean());
      if (shape.pointAtV1) P.col(P.cols() - 1).setConstant(P.col(P.cols() - 1).mean());
    }
    // Measure at the check parameters against the FFD of the original.
    const Eigen::MatrixXd cuBasis = basisMatrix(fu, degreeU, cu), cvBasis = basisMatrix(fv, degreeV, cv);
    const Eigen::MatrixX3d expected = ffdOfGrid(cu, cv);
    Eigen::MatrixXd error = Eigen::MatrixXd::Zero(cu.size(), cv.size());
    for (int c = 0; c < 3; ++c) {
      const Eigen::MatrixXd fitted = cuBasis * poles[c] * cvBasis.transpose();
      const Eigen::MatrixXd want = Eigen::Map<const Eigen::MatrixXd>(expected.col(c).data(), cu.size(), cv.size());
      error.array() += (fitted - want).array().square();
    }
    error = error.cwiseSqrt();
    TColgp_Array2OfPnt grid(1, static_cast<Standard_Integer>(poles[0].rows()), 1, static_cast<Standard_Integer>(poles[0].cols()));
    for (Eigen::Index i = 0; i < poles[0].rows(); ++i)
      for (Eigen::Index j = 0; j < poles[0].cols(); ++j)
        grid(static_cast<Standard_Integer>(i + 1), static_cast<Standard_Integer>(j + 1)) = gp_Pnt(poles[0](i, j), poles[1](i, j), poles[2](i, j));
    const KnotArrays ku = knotArrays(fu), kv = knotArrays(fv);
    fit.surface = new Geom_BSplineSurface(grid, ku.knots, kv.knots, ku.mults, kv.mults, degreeU, degreeV);
    fit.error = error.maxCoeff();
    if (fit.error <= tolerance || round == kMaxRounds) break;
    std::vector<char> markU(bu.spans(), 0), markV(bv.spans(), 0);
    for (Eigen::Index i = 0; i < error.rows(); ++i)
      for (Eigen::Index j = 0; j < error.cols(); ++j)
        if (error(i, j) > tolerance) markU[spanU[i]] = markV[spanV[j]] = 1;
    const bool finerU = refine(bu, markU);
    const bool finerV = refine(bv, markV);
    if (!finerU && !finerV) break;
  }
  return fit;
}

CurveFit fitCurve(const FfdMap& map, const Handle(Geom_BSplineCurve)& curve, double t0, double t1, int degree,
                  double tolerance, const std::vector<double>& kinks) {
  TColStd_Array1OfReal knots(1, curve->NbKnots());
  TColStd_Array1OfInteger mults(1, curve->NbKnots());
  curve->Knots(knots);
  curve->Multiplicities(mults);
  Breaks b = initialBreaks(knots, mults, curve->Degree(), t0, t1, kinks);
  CurveFit fit;
  auto ffdOf = [&](const std::vector<double>& ts) {
    Eigen::MatrixX3d world(static_cast<Eigen::Index>(ts.size()), 3);
    for (std::size_t i = 0; i < ts.size(); ++i) {
      const gp_Pnt p = curve->Value(ts[i]);
      world.row(static_cast<Eigen::Index>(i)) << p.X(), p.Y(), p.Z();
    }
    return map.points(world);
  };
  for (int round = 0;; ++round) {
    std::vector<double> samples, checks;
    std::vector<int> spanOf;
    parameters(b, degree, samples, checks, spanOf);
    const std::vector<double> flat = flatKnots(b, degree);
    const Eigen::MatrixXd n = basisMatrix(flat, degree, samples);
    const Eigen::MatrixXd poles = n.colPivHouseholderQr().solve(Eigen::MatrixXd(ffdOf(samples)));
    const Eigen::MatrixXd fitted = basisMatrix(flat, degree, checks) * poles;
    const Eigen::VectorXd error = (fitted - Eigen::MatrixXd(ffdOf(checks))).rowwise().norm();
    TColgp_Array1OfPnt points(1, static_cast<Standard_Integer>(poles.rows()));
    for (Eigen::Index i = 0; i < poles.rows(); ++i)
      points(static_cast<Standard_Integer>(i + 1)) = gp_Pnt(poles(i, 0), poles(i, 1), poles(i, 2));
    const KnotArrays k = knotArrays(flat);
    fit.curve = new Geom_BSplineCurve(points, k.knots, k.mults, degree);
    fit.error = error.maxCoeff();
    if (fit.error <= tolerance || round == kMaxRounds) break;
    std::vector<char> mark(b.spans(), 0);
    for (Eigen::Index i = 0; i < error.size(); ++i)
      if (error[i] > tolerance) mark[spanOf[i]] = 1;
    if (!refine(b, mark)) break;
  }
  return fit;
}

}  // namespace ffdkit::cad
