// The exact FFD of a B-spline surface or curve when the lattice's FFD is one polynomial per cell:
// split where the geometry crosses the knot planes, each piece composed with its cell's polynomial.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>

#include "ffd_map.h"

namespace ffdkit::cad {

/// A composed surface, or null and why it could not be composed exactly.
struct ExactSurface {
  Handle(Geom_BSplineSurface) surface;
  std::string whyNot;
};

/// A composed curve, or null and why not.
struct ExactCurve {
  Handle(Geom_BSplineCurve) curve;
  std::string whyNot;
};

/// Planes of constant lattice parameter, per axis (u, v, w).
using Planes = std::array<std::vector<double>, 3>;

/// Where a clamped B-spline surface (world coordinates) crosses the planes along its own parameter
/// lines: the u and v values of those lines (a plane's coordinate depends on one patch parameter
/// only, piece by piece; the crossing is a root of a Bernstein polynomial). `across` describes the
/// first crossing that is not a parameter line (empty: none).
struct SurfaceCrossings {
  std::vector<double> u;
  std::vector<double> v;
  std::string across;
};
SurfaceCrossings parameterLineCrossings(const FfdMap& map, const Handle(Geom_BSplineSurface)& surface, const Planes& planes);

/// The parameters where a clamped B-spline curve crosses the planes.
std::vector<double> curveCrossings(const FfdMap& map, const Handle(Geom_BSplineCurve)& curve, const Planes& planes);

/// X(S) for a clamped B-spline surface S in world coordinates and a polynomial() map. S is split
/// into Bezier pieces at its knots and, where a piece crosses a knot plane of the lattice along one
/// of its parameter lines (the plane's coordinate depends on one patch parameter only: a plane,
/// cylinder or extrusion aligned with the lattice), at the crossing (a root of a Bernstein
/// polynomial); every piece is then composed with the polynomial of the cell it lies in
/// (composeBezierPatch), the pieces joined on their knots, and each knot removed down to the
/// continuity of the original there (or, at a crossing, as far as OpenCASCADE can within 1e-12 of
/// the poles' extent). The parameters are S's, so p-curves stay valid. Beyond the lattice the end
/// cells' polynomials apply (the caller decides whether that is the FFD there). Null with a reason
/// when a piece crosses a knot plane across its parameter lines.
ExactSurface composeSurfaceExactly(const FfdMap& map, const Handle(Geom_BSplineSurface)& surface);

/// The same for a clamped B-spline curve (a crossing is always a parameter: never null for a
/// polynomial() map).
ExactCurve composeCurveExactly(const FfdMap& map, const Handle(Geom_BSplineCurve)& curve);

}  // namespace ffdkit::cad
