#pragma once

#include <string>
#include <vector>

#include "ffdkit/cad/cad_model.h"
#include "ffdkit/ffd/lattice.h"

namespace ffdkit::cad {

/// How a CAD model is deformed.
enum class CadMethod {
  /// The lattice's polynomial composed exactly with every surface and curve (composeBezierPatch):
  /// the written surfaces are the FFD of the original ones, to rounding.
  Exact,
  /// Each NURBS pole moved by the FFD (PyGeM's CAD FFD): not the FFD of the surface, and faces and
  /// edges that share a boundary move it differently (gaps). Offered for comparison.
  Poles
};

/// Options of deformCad().
struct CadDeformOptions {
  CadMethod method = CadMethod::Exact;  ///< exact composition (default) or pole moving
  /// Exact method: the highest degree per direction a composed surface or curve may have (at
  /// most 25, OpenCASCADE's limit). A composition above it is approximated (see `approximate`).
  int maxDegree = 15;
  /// Exact method: what cannot be composed exactly is approximated within `tolerance` (true) or
  /// refused with a CadError (false). That is a composed degree above maxDegree; a face that
  /// crosses a knot plane of a B-spline lattice other than along its own parameter lines; a face
  /// or edge that leaves the lattice (with the Identity, ClampEdge or Falloff outside policy the
  /// FFD is not one polynomial across the lattice's boundary); and every face and edge of a
  /// lattice whose rest shape is not a box (a cylindrical lattice).
  bool approximate = true;
  /// The largest distance an approximated surface or curve may have from the FFD of the original
  /// (model units); 0 = 1e-6 x the model's bounding-box diagonal. An approximation that cannot
  /// reach it is a CadError.
  double tolerance = 0.0;
  /// > 0: measure the result on a samples x samples grid per face (deviation from the FFD of the
  /// original surface at the same parameters, at the grid points inside the face's trim) and on
  /// `samples` points per edge (gaps); 0: skip.
  int samples = 0;
};

/// What deformCad() made and measured.
struct CadDeformReport {
  int faces = 0;              ///< faces deformed
  int edges = 0;              ///< edges deformed
  int maxDegree = 0;          ///< the highest degree of a deformed surface or curve
  int approximatedFaces = 0;  ///< faces whose surface was approximated (not composed exactly)
  int approximatedEdges = 0;  ///< edges whose curve was approximated
  /// The tolerance the approximations were held to (model units; 0 when there was none).
  double tolerance = 0.0;
  /// The largest distance between an approximated surface or curve and the FFD of the original at
  /// the same parameters, measured by the approximation on a grid denser than its fit (always
  /// measured; 0 without approximations).
  double approximationError = 0.0;
  /// One line per approximated face or edge: "part 'x', face 3: <why>".
  std::vector<std::string> approximations;
  double maxDeviation = 0.0;  ///< with samples > 0: max |S'(s,t) - X(S(s,t))| over the samples
  double maxGap = 0.0;        ///< with samples > 0: max distance between an edge's curve and its faces
  double seconds = 0.0;       ///< wall time of the deformation (without the measuring)
};

/// A deformed model and its report.
struct CadDeformResult {
  CadModel model;          ///< same parts and names, deformed
  CadDeformReport report;  ///< degrees, time and the measures
};

/// Deforms every part of the model by the lattice's FFD (world coordinates), keeping the topology:
/// every vertex, edge and face goes through the same map (BRepTools_Modifier), so faces that
/// shared an edge still share it. Analytic surfaces and curves are first converted to their exact
/// NURBS form (BRepBuilderAPI_NurbsConvert); each NURBS is split at its knots into Bezier pieces,
/// each piece composed (Exact) or its poles moved (Poles), and the pieces joined again on the
/// same knots, so the p-curves stay valid unchanged.
/// Exact: the FFD of a box lattice is one polynomial per lattice cell (a Bernstein lattice has one
/// cell; a B-spline lattice's cells are converted to Bernstein form). A surface or curve is first
/// split where it crosses a knot plane (exactly, for a curve and for a surface whose crossing is
/// one of its parameter lines), so that each piece lies in one cell and is composed with that
/// cell's polynomial. Where the FFD of the geometry is not one polynomial per piece, or the
/// composed degree is above maxDegree, the geometry is approximated (options.approximate) by a
/// least-squares B-spline on the same parameters, refined until it is within the tolerance of the
/// FFD, and the report says which faces and edges and why. Containment in a cell or in the lattice
/// is checked at sample points (the control hull first; 17 x 17 per face piece), not proven.
/// @throws CadError naming the part and face when a condition fails, an approximation cannot
///         reach the tolerance, or OpenCASCADE throws.
CadDeformResult deformCad(const CadModel& model, const ffd::Lattice& lattice, const CadDeformOptions& options = {});

}  // namespace ffdkit::cad
