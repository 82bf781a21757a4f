// Approximating the FFD of a B-spline surface or curve by a polynomial B-spline on the same
// parameters (so that the p-curves of the faces stay valid), to a tolerance.
#pragma once

#include <vector>

#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>

#include "ffd_map.h"

namespace ffdkit::cad {

/// A fitted surface and the largest distance from the FFD of the original measured at its check
/// parameters (the span ends and the midpoints between the fit's own samples).
struct SurfaceFit {
  Handle(Geom_BSplineSurface) surface;
  double error = 0.0;
};

/// A fitted curve and its measured error, as SurfaceFit.
struct CurveFit {
  Handle(Geom_BSplineCurve) curve;
  double error = 0.0;
};

/// Least-squares fit of X(S(u, v)) on [u0, u1] x [v0, v1] (inside S's domain; S in world
/// coordinates, X = map.points) by a non-rational B-spline of the given degrees. The knots start
/// at S's own knots in the rectangle (with S's continuity there, at most degree - 1), at least 4
/// spans per direction; spans where the error exceeds `tolerance` are halved, up to 6 times and
/// 96 spans per direction. The result may miss the tolerance: compare its error.
/// extend: fit the FFD continued beyond the lattice (FfdMap::points), for a face whose trim lies
/// inside it. `kinksU`, `kinksV`: parameter lines where the FFD of S is only C0 (where S crosses the lattice's
/// boundary or knot planes): knots of full multiplicity there.
SurfaceFit fitSurface(const FfdMap& map, const Handle(Geom_BSplineSurface)& surface, double u0, double u1, double v0,
                      double v1, int degreeU, int degreeV, double tolerance, bool extend, const std::vector<double>& kinksU = {},
                      const std::vector<double>& kinksV = {});

/// The same for a curve on [t0, t1].
CurveFit fitCurve(const FfdMap& map, const Handle(Geom_BSplineCurve)& curve, double t0, double t1, int degree,
                  double tolerance, const std::vector<double>& kinks = {});

}  // namespace ffdkit::cad
