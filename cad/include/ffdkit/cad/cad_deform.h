#pragma once

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
  /// Exact method: the highest degree per direction a composed surface or curve may reach (at
  /// most 25, OpenCASCADE's limit); above it deformCad throws (approximation is not implemented).
  int maxDegree = 15;
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
/// Exact needs a Bernstein lattice with a box rest shape, and each part inside the lattice (or the
/// Extrapolate outside policy), where the FFD is one polynomial: checked at every vertex, at 33
/// points per edge and on a 17 x 17 grid per face inside its trim (a sampled check, not a proof).
/// @throws CadError naming the part and face when a condition fails or OpenCASCADE throws.
CadDeformResult deformCad(const CadModel& model, const ffd::Lattice& lattice, const CadDeformOptions& options = {});

}  // namespace ffdkit::cad
