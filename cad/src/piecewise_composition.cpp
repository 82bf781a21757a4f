#include "piecewise_composition.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array2OfPnt.hxx>

#include "ffdkit/cad/bernstein_composition.h"

#include "occt_points.h"

namespace ffdkit::cad {

namespace {

using detail::toEigen;
using detail::toPnt;

const char* const kAxisNames[3] = {"u", "v", "w"};

/// Value of the Bernstein polynomial with coefficients c at s (de Casteljau).
double bernsteinValue(std::vector<double> c, double s) {
  for (std::size_t level = c.size() - 1; level > 0; --level)
    for (std::size_t i = 0; i < level; ++i) c[i] = (1.0 - s) * c[i] + s * c[i + 1];
  return c[0];
}

/// The roots in (0, 1) where the Bernstein polynomial c changes sign: found on a grid of 64
/// intervals, refined by bisection to rounding. A touch without a sign change is no crossing.
std::vector<double> signChanges(const std::vector<double>& c) {
  const int n = 64;
  std::vector<double> value(n + 1);
  for (int i = 0; i <= n; ++i) value[i] = bernsteinValue(c, double(i) / n);
  std::vector<double> roots;
  for (int i = 1; i <= n; ++i) {
    if (value[i] == 0.0 && i < n && value[i - 1] * value[i + 1] < 0.0) roots.push_back(double(i) / n);
    if (value[i - 1] * value[i] >= 0.0) continue;
    double lo = double(i - 1) / n, hi = double(i) / n;
    const bool rising = value[i - 1] < 0.0;
    for (int step = 0; step < 60 && hi - lo > 1e-16; ++step) {
      const double mid = 0.5 * (lo + hi);
      ((bernsteinValue(c, mid) < 0.0) == rising ? lo : hi) = mid;
    }
    roots.push_back(0.5 * (lo + hi));
  }
  std::vector<double> inside;
  for (double r : roots)
    if (r > 1e-12 && r < 1.0 - 1e-12) inside.push_back(r);
  return inside;
}

/// The cell of a piece along one axis: the interval of lattice parameters it must stay in (the
/// end cells reach to infinity: the policy beyond the lattice is the caller's).
std::pair<double, double> cellRange(const ffd::AxisSpline& axis, int cell) {
  const double inf = std::numeric_limits<double>::infinity();
  return {cell == 0 ? -inf : axis.cellMin(cell), cell + 1 == axis.cellCount() ? inf : axis.cellMax(cell)};
}

/// The knot parameters where the geometry is split, deduplicated against each other and the
/// existing knots (within `eps`).
void addSplit(std::vector<double>& splits, double at) { splits.push_back(at); }

std::vector<double> distinctSplits(std::vector<double> splits, const TColStd_Array1OfReal& knots, double eps) {
  std::sort(splits.begin(), splits.end());
  std::vector<double> out;
  for (double s : splits) {
    if (!out.empty() && s - out.back() <= eps) continue;
    bool existing = false;
    for (Standard_Integer i = knots.Lower(); i <= knots.Upper(); ++i) existing = existing || std::abs(knots(i) - s) <= eps;
    if (!existing) out.push_back(s);
  }
  return out;
}

/// Reduces the multiplicity of knot `index` to `desired`, or as close to it as OpenCASCADE can
/// within `tolerance` (a failed removal leaves the geometry as it was).
template <class Remove>
void reduceKnot(int multiplicity, int desired, Remove&& remove) {
  for (int m = std::max(1, desired); m < multiplicity; ++m)
    if (remove(m)) return;
}

/// Knot removal may move the geometry by 1e-12 of the poles' extent (rounding, for a join that is
/// as smooth as the original's).
double removalTolerance(const TColgp_Array2OfPnt& poles) {
  Eigen::AlignedBox3d box;
  for (Standard_Integer i = poles.LowerRow(); i <= poles.UpperRow(); ++i)
    for (Standard_Integer j = poles.LowerCol(); j <= poles.UpperCol(); ++j) box.extend(toEigen(poles(i, j)));
  return 1e-12 * std::max(box.diagonal().norm(), 1e-300);
}

/// The continuity C^k of the original at each of its interior knots (k = degree - multiplicity).
template <class Knot, class Mult>
std::map<double, int> continuityAt(int count, int degree, Knot&& knot, Mult&& mult) {
  std::map<double, int> out;
  for (Standard_Integer i = 2; i < count; ++i) out[knot(i)] = degree - mult(i);
  return out;
}

/// The multiplicity of a composed knot of degree `composed` where the original (degree p) was
/// C^k: composed - k; at a knot-plane crossing (not an original knot) as far down as possible.
int desiredMultiplicity(const std::map<double, int>& continuity, double knot, int composed) {
  const auto found = continuity.find(knot);
  return found == continuity.end() ? 1 : std::max(0, composed - found->second);
}

/// The crossings of an extracted (Bezier-jointed) surface with the planes, as SurfaceCrossings.
SurfaceCrossings crossingsOfExtracted(const FfdMap& map, const Handle(Geom_BSplineSurface)& bs, const Planes& planes) {
  const int p = bs->UDegree();
  const int q = bs->VDegree();
  const bool rational = bs->IsURational() || bs->IsVRational();
  auto weight = [&](int i, int j) { return rational ? bs->Weight(i, j) : 1.0; };
  SurfaceCrossings out;
  std::vector<double>& splitU = out.u;
  std::vector<double>& splitV = out.v;
  for (int axis = 0; axis < 3; ++axis) {
    for (double plane : planes[axis]) {
      for (Standard_Integer su = 0; su + 1 < bs->NbUKnots(); ++su)
        for (Standard_Integer sv = 0; sv + 1 < bs->NbVKnots(); ++sv) {
          Eigen::MatrixXd alpha(p + 1, q + 1), w(p + 1, q + 1);
          for (int a = 0; a <= p; ++a)
            for (int b = 0; b <= q; ++b) {
              alpha(a, b) = map.parameters(toEigen(bs->Pole(su * p + a + 1, sv * q + b + 1)))[axis] - plane;
              w(a, b) = weight(su * p + a + 1, sv * q + b + 1);
            }
          const double eps = 1e-12 * (1.0 + std::abs(plane));
          if (alpha.minCoeff() >= -eps || alpha.maxCoeff() <= eps) continue;  // the hull is on one side
          bool onlyS = true, onlyT = true;
          for (int a = 0; a <= p; ++a)
            for (int b = 0; b <= q; ++b) {
              const bool separable = std::abs(w(a, b) * w(0, 0) - w(a, 0) * w(0, b)) <= 1e-12 * w(a, b) * w(0, 0);
              onlyS = onlyS && separable && std::abs(alpha(a, b) - alpha(a, 0)) <= eps;
              onlyT = onlyT && separable && std::abs(alpha(a, b) - alpha(0, b)) <= eps;
            }
          const double u0 = bs->UKnot(su + 1), u1 = bs->UKnot(su + 2), v0 = bs->VKnot(sv + 1), v1 = bs->VKnot(sv + 2);
          if (onlyS || onlyT) {
            std::vector<double> c;
            if (onlyS)
              for (int a = 0; a <= p; ++a) c.push_back(w(a, 0) * alpha(a, 0));
            else
              for (int b = 0; b <= q; ++b) c.push_back(w(0, b) * alpha(0, b));
            for (double s : signChanges(c)) {
              if (onlyS) addSplit(splitU, u0 + (u1 - u0) * s);
              else addSplit(splitV, v0 + (v1 - v0) * s);
            }
            continue;
          }
          // Across the parameter lines: a real crossing unless the hull alone straddles the plane.
          double lo = std::numeric_limits<double>::infinity(), hi = -lo;
          for (int i = 0; i <= 16; ++i)
            for (int j = 0; j <= 16; ++j) {
              const double t = map.parameters(toEigen(bs->Value(u0 + (u1 - u0) * i / 16, v0 + (v1 - v0) * j / 16)))[axis] - plane;
              lo = std::min(lo, t);
              hi = std::max(hi, t);
            }
          if (lo < -eps && hi > eps && out.across.empty())
            out.across = "it crosses the lattice's knot plane " + std::string(kAxisNames[axis]) + " = " +
                         std::to_string(plane) + " across its parameter lines (the FFD is two polynomials there)";
        }
    }
  }
  return out;
}

}  // namespace

SurfaceCrossings parameterLineCrossings(const FfdMap& map, const Handle(Geom_BSplineSurface)& surface, const Planes& planes) {
  Handle(Geom_BSplineSurface) bs = Handle(Geom_BSplineSurface)::DownCast(surface->Copy());
  for (Standard_Integer i = 2; i < bs->NbUKnots(); ++i) bs->IncreaseUMultiplicity(i, bs->UDegree());
  for (Standard_Integer i = 2; i < bs->NbVKnots(); ++i) bs->IncreaseVMultiplicity(i, bs->VDegree());
  return crossingsOfExtracted(map, bs, planes);
}

std::vector<double> curveCrossings(const FfdMap& map, const Handle(Geom_BSplineCurve)& curve, const Planes& planes) {
  Handle(Geom_BSplineCurve) bs = Handle(Geom_BSplineCurve)::DownCast(curve->Copy());
  const int p = bs->Degree();
  for (Standard_Integer i = 2; i < bs->NbKnots(); ++i) bs->IncreaseMultiplicity(i, p);
  const bool rational = bs->IsRational();
  auto weight = [&](int i) { return rational ? bs->Weight(i) : 1.0; };
  std::vector<double> splits;
  for (int axis = 0; axis < 3; ++axis)
    for (double plane : planes[axis])
      for (Standard_Integer s = 0; s + 1 < bs->NbKnots(); ++s) {
        std::vector<double> c;
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (int a = 0; a <= p; ++a) {
          const double alpha = map.parameters(toEigen(bs->Pole(s * p + a + 1)))[axis] - plane;
          lo = std::min(lo, alpha);
          hi = std::max(hi, alpha);
          c.push_back(weight(s * p + a + 1) * alpha);
        }
        const double eps = 1e-12 * (1.0 + std::abs(plane));
        if (lo >= -eps || hi <= eps) continue;
        const double t0 = bs->Knot(s + 1), t1 = bs->Knot(s + 2);
        for (double r : signChanges(c)) addSplit(splits, t0 + (t1 - t0) * r);
      }
  return splits;
}

ExactSurface composeSurfaceExactly(const FfdMap& map, const Handle(Geom_BSplineSurface)& input) {
  Handle(Geom_BSplineSurface) bs = Handle(Geom_BSplineSurface)::DownCast(input->Copy());
  const int p = bs->UDegree();
  const int q = bs->VDegree();
  const int d = map.totalDegree();
  const std::map<double, int> continuityU =
      continuityAt(bs->NbUKnots(), p, [&](int i) { return bs->UKnot(i); }, [&](int i) { return bs->UMultiplicity(i); });
  const std::map<double, int> continuityV =
      continuityAt(bs->NbVKnots(), q, [&](int i) { return bs->VKnot(i); }, [&](int i) { return bs->VMultiplicity(i); });
  // Bezier extraction by knot insertion: the pieces share their boundary poles and weights exactly.
  auto extract = [&] {
    for (Standard_Integer i = 2; i < bs->NbUKnots(); ++i) bs->IncreaseUMultiplicity(i, p);
    for (Standard_Integer i = 2; i < bs->NbVKnots(); ++i) bs->IncreaseVMultiplicity(i, q);
  };
  extract();
  const bool rational = bs->IsURational() || bs->IsVRational();

  // Where a piece crosses a knot plane along a parameter line, split it there.
  const Planes planes{map.knotPlanes(0), map.knotPlanes(1), map.knotPlanes(2)};
  const SurfaceCrossings crossings = crossingsOfExtracted(map, bs, planes);
  if (!crossings.across.empty()) return {nullptr, crossings.across};
  const std::vector<double>& splitU = crossings.u;
  const std::vector<double>& splitV = crossings.v;
  {
    TColStd_Array1OfReal uk(1, bs->NbUKnots()), vk(1, bs->NbVKnots());
    bs->UKnots(uk);
    bs->VKnots(vk);
    for (double u : distinctSplits(splitU, uk, 1e-12 * (uk(uk.Upper()) - uk(uk.Lower())))) bs->InsertUKnot(u, p, 0.0);
    for (double v : distinctSplits(splitV, vk, 1e-12 * (vk(vk.Upper()) - vk(vk.Lower())))) bs->InsertVKnot(v, q, 0.0);
  }

  const int nu = bs->NbUKnots() - 1;
  const int nv = bs->NbVKnots() - 1;
  const int du = d * p;
  const int dv = d * q;
  TColgp_Array2OfPnt poles(1, nu * du + 1, 1, nv * dv + 1);
  TColStd_Array2OfReal weights(1, nu * du + 1, 1, nv * dv + 1);
  BezierPatch piece;
  piece.degreeU = p;
  piece.degreeV = q;
  piece.poles.resize(piece.poleCount(), 3);
  if (rational) piece.weights.resize(piece.poleCount());
  for (int sv = 0; sv < nv; ++sv)
    for (int su = 0; su < nu; ++su) {
      const double u0 = bs->UKnot(su + 1), u1 = bs->UKnot(su + 2), v0 = bs->VKnot(sv + 1), v1 = bs->VKnot(sv + 2);
      // The piece's cell (from its middle), its samples checked to stay in it.
      const Eigen::Vector3d middle = map.parameters(toEigen(bs->Value(0.5 * (u0 + u1), 0.5 * (v0 + v1))));
      Eigen::Vector3i cell;
      for (int a = 0; a < 3; ++a) cell[a] = map.cellOf(a, middle[a]);
      for (int i = 0; i <= 8; ++i)
        for (int j = 0; j <= 8; ++j) {
          const Eigen::Vector3d t = map.parameters(toEigen(bs->Value(u0 + (u1 - u0) * i / 8, v0 + (v1 - v0) * j / 8)));
          for (int a = 0; a < 3; ++a) {
            const auto [lo, hi] = cellRange(map.lattice().axis(a), cell[a]);
            const double eps = 1e-9 * (map.lattice().parameterMax()[a] - map.lattice().parameterMin()[a]);
            if (t[a] < lo - eps || t[a] > hi + eps)
              return {nullptr, "a piece of it spans two lattice cells along " + std::string(kAxisNames[a]) +
                                   " where no crossing could be split"};
          }
        }
      for (int b = 0; b <= q; ++b)
        for (int a = 0; a <= p; ++a) {
          const Eigen::Index row = a + (p + 1) * b;
          piece.poles.row(row) = toEigen(bs->Pole(su * p + a + 1, sv * q + b + 1)).transpose();
          if (rational) piece.weights[row] = bs->Weight(su * p + a + 1, sv * q + b + 1);
        }
      const BezierPatch composed = composeBezierPatch(map.cellVolume(cell), piece);
      for (int b = 0; b <= dv; ++b)
        for (int a = 0; a <= du; ++a) {
          const Eigen::Index row = a + (du + 1) * b;
          poles(su * du + a + 1, sv * dv + b + 1) = toPnt(composed.poles.row(row).transpose());
          weights(su * du + a + 1, sv * dv + b + 1) = rational ? composed.weights[row] : 1.0;
        }
    }
  TColStd_Array1OfReal uk(1, nu + 1), vk(1, nv + 1);
  bs->UKnots(uk);
  bs->VKnots(vk);
  TColStd_Array1OfInteger um(1, nu + 1), vm(1, nv + 1);
  for (Standard_Integer i = 1; i <= nu + 1; ++i) um(i) = (i == 1 || i == nu + 1) ? du + 1 : du;
  for (Standard_Integer i = 1; i <= nv + 1; ++i) vm(i) = (i == 1 || i == nv + 1) ? dv + 1 : dv;
  Handle(Geom_BSplineSurface) out = rational ? new Geom_BSplineSurface(poles, weights, uk, vk, um, vm, du, dv)
                                             : new Geom_BSplineSurface(poles, uk, vk, um, vm, du, dv);
  // The composition of a C^k join is C^k: remove the knots the C0 join of the pieces added, where
  // OpenCASCADE finds them removable within rounding.
  const double tolerance = removalTolerance(poles);
  for (Standard_Integer i = 2; i <= nu; ++i)
    reduceKnot(du, desiredMultiplicity(continuityU, uk(i), du), [&](int m) { return out->RemoveUKnot(i, m, tolerance); });
  for (Standard_Integer i = 2; i <= nv; ++i)
    reduceKnot(dv, desiredMultiplicity(continuityV, vk(i), dv), [&](int m) { return out->RemoveVKnot(i, m, tolerance); });
  return {out, {}};
}

ExactCurve composeCurveExactly(const FfdMap& map, const Handle(Geom_BSplineCurve)& input) {
  Handle(Geom_BSplineCurve) bs = Handle(Geom_BSplineCurve)::DownCast(input->Copy());
  const int p = bs->Degree();
  const int d = map.totalDegree();
  const std::map<double, int> continuity =
      continuityAt(bs->NbKnots(), p, [&](int i) { return bs->Knot(i); }, [&](int i) { return bs->Multiplicity(i); });
  for (Standard_Integer i = 2; i < bs->NbKnots(); ++i) bs->IncreaseMultiplicity(i, p);
  const bool rational = bs->IsRational();
  const std::vector<double> splits = curveCrossings(map, bs, {map.knotPlanes(0), map.knotPlanes(1), map.knotPlanes(2)});
  {
    TColStd_Array1OfReal knots(1, bs->NbKnots());
    bs->Knots(knots);
    for (double t : distinctSplits(splits, knots, 1e-12 * (knots(knots.Upper()) - knots(knots.Lower()))))
      bs->InsertKnot(t, p, 0.0);
  }
  const int n = bs->NbKnots() - 1;
  const int dp = d * p;
  TColgp_Array1OfPnt poles(1, n * dp + 1);
  TColStd_Array1OfReal weights(1, n * dp + 1);
  BezierPatch piece;
  piece.degreeU = p;
  piece.degreeV = 0;
  piece.poles.resize(p + 1, 3);
  if (rational) piece.weights.resize(p + 1);
  for (int s = 0; s < n; ++s) {
    const double t0 = bs->Knot(s + 1), t1 = bs->Knot(s + 2);
    const Eigen::Vector3d middle = map.parameters(toEigen(bs->Value(0.5 * (t0 + t1))));
    Eigen::Vector3i cell;
    for (int a = 0; a < 3; ++a) cell[a] = map.cellOf(a, middle[a]);
    for (int a = 0; a <= p; ++a) {
      piece.poles.row(a) = toEigen(bs->Pole(s * p + a + 1)).transpose();
      if (rational) piece.weights[a] = bs->Weight(s * p + a + 1);
    }
    const BezierPatch composed = composeBezierPatch(map.cellVolume(cell), piece);
    for (int a = 0; a <= dp; ++a) {
      poles(s * dp + a + 1) = toPnt(composed.poles.row(a).transpose());
      weights(s * dp + a + 1) = rational ? composed.weights[a] : 1.0;
    }
  }
  TColStd_Array1OfReal knots(1, n + 1);
  bs->Knots(knots);
  TColStd_Array1OfInteger mults(1, n + 1);
  for (Standard_Integer i = 1; i <= n + 1; ++i) mults(i) = (i == 1 || i == n + 1) ? dp + 1 : dp;
  Handle(Geom_BSplineCurve) out = rational ? new Geom_BSplineCurve(poles, weights, knots, mults, dp)
                                           : new Geom_BSplineCurve(poles, knots, mults, dp);
  TColgp_Array2OfPnt asGrid(1, poles.Length(), 1, 1);
  for (Standard_Integer i = 1; i <= poles.Length(); ++i) asGrid(i, 1) = poles(i);
  const double tolerance = removalTolerance(asGrid);
  for (Standard_Integer i = 2; i <= n; ++i)
    reduceKnot(dp, desiredMultiplicity(continuity, knots(i), dp), [&](int m) { return out->RemoveKnot(i, m, tolerance); });
  return {out, {}};
}

}  // namespace ffdkit::cad
