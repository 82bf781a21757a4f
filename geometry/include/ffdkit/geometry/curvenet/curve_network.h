#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/geometry/curvenet/network_curve.h"

namespace ffdkit::geometry::curvenet {

/// One input curve of a network, plain data (what a scene file holds; JSON shape in
/// docs/geometry-curvenet.md).
struct CurveDescription {
  /// How the curve is given.
  enum class Kind { Polyline, BSpline };
  std::string name;                   ///< for messages; "" -> "curve <index>"
  Kind kind = Kind::Polyline;         ///< Polyline: C^2 cubic spline through `points`
  Eigen::MatrixX3d points;            ///< Polyline: points to interpolate; BSpline: control points
  bool closed = false;                ///< closed (periodic) curve; do not repeat the first point
  KnotSpacing spacing = KnotSpacing::ChordLength;  ///< Polyline only
  int degree = 3;                     ///< BSpline only
  std::vector<double> knots;          ///< BSpline only, see bsplineCurve()
  std::optional<Plane> plane;         ///< drawing plane; default: fitted if the curve is planar
  double influence = 1.0;             ///< w_c > 0 of the sweep weights g (sec. 5.2.1)
};

/// A whole network, plain data.
struct CurveNetworkDescription {
  std::vector<CurveDescription> curves;  ///< the input curves, in order
};

/// Options of network construction (Kuriyama 1996, sec. 5.3.3).
struct CurveNetworkOptions {
  /// tau: two curves closer than this intersect. 0 -> 0.01 x bounding-box diagonal (
  /// Kuriyama 1996, sec. 5.3.3).
  double intersectionTolerance = 0.0;
  /// Crossing angle below which two curves count as tangent / near-coincident (error), degrees.
  double minimumCrossingAngleDegrees = 2.0;
  /// epsilon_s of the face tracing: turns within this of straight are "straight on", degrees.
  double straightAngleDegrees = 5.0;
  /// Orientation used only for a connected part where no vertex normal is determined by the
  /// thesis' rule N.1-N.4 (e.g. a sheet of straight curves): normals get n . hint >= 0 there.
  Eigen::Vector3d orientationHint = Eigen::Vector3d::UnitZ();
  /// Rule (c): fill every open chain that runs from a free end to a free end, closed by a
  /// virtual side (Kuriyama 1996, secs. 5.2.4 (c), 5.3.4: only when the user asks). false:
  /// report them.
  bool fillOpenRegions = false;
};

/// A network input error: which curve(s), where, and what was expected.
class CurveNetworkError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A parameter on a curve of the network.
struct CurvePoint {
  int curve = -1;  ///< index of the curve
  double parameter = 0.0;  ///< parameter on it
};

/// A vertex of the network: where curves cross or meet, or a free end.
struct NetworkVertex {
  /// What meets at the vertex.
  enum class Kind {
    Crossing,   ///< two curves cross
    TJunction,  ///< an open curve ends on a curve passing through
    Multiple,   ///< >= 3 curves (Kuriyama 1996, sec. 5.2.4 (a))
    FreeEnd     ///< the free end of an open curve (not an intersection)
  };
  Kind kind = Kind::Crossing;  ///< what meets there
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< where it lies
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< tangent-plane normal, Kuriyama 1996, sec. 5.3.3
  bool normalFromRule = false;  ///< true: N.1-N.4; false: propagated or from the hint
  std::vector<CurvePoint> curves;  ///< one entry per curve through or ending at the vertex
};

/// A half-edge: the piece of `curve` from vertex `from` (parameter tFrom) to `to` (tTo),
/// traversed with sign = +1 (increasing t) or -1. For sign +1, tTo > tFrom (may exceed the
/// period of a closed curve: evaluate periodically).
struct HalfEdge {
  int curve = -1;  ///< the curve it runs along
  ///@{
  /// Start and end vertex.
  int from = -1, to = -1;
  ///@}
  ///@{
  /// Curve parameters at the start and end vertex.
  double tFrom = 0.0, tTo = 0.0;
  ///@}
  int sign = 1;  ///< +1: traversed with increasing t; -1: decreasing
  int twin = -1;  ///< the opposite half-edge
  int next = -1;   ///< deterministic next (Kuriyama 1996, sec. 5.3.3), -1 at a dead end
  int face = -1;   ///< -1: not on a face (dangling, or on an open chain)
  int run = -1;    ///< the run of its edge (a dangling piece is a run of its own)
  bool dangling = false;  ///< on no face: a piece that ends at a free end
};

/// The curves at one end of a run used as transversal (several: the average of rule (a);
/// none at a free end, where the sweep is the single sweep of the other end, rule (c)).
/// member k contributes K_k(parameter + direction * s) - X for s > 0 on the left of the run.
struct Transversal {
  int vertex = -1;  ///< the network vertex at this end
  std::vector<CurvePoint> members;  ///< the transversal curves and their parameters at the vertex
  std::vector<int> directions;  ///< +-1 per member
  double influence = 1.0;       ///< mean influence of the members (w of g, sec. 5.2.1)
};

/// A run (Kuriyama 1996, sec. 5.3.4): the maximal piece of one curve between vertices where another
/// curve passes through (or the curve ends). It carries the sweep shared by the faces on both
/// sides.
struct Run {
  int curve = -1;  ///< the curve it lies on
  ///@{
  /// Curve parameters at the run's start and end.
  double tStart = 0.0, tEnd = 0.0;  ///< tEnd > tStart, increasing curve parameter
  ///@{
  /// Network vertices at the run's start and end.
  int vertexStart = -1, vertexEnd = -1;
  ///@}
  ///@}
  std::vector<int> edges;           ///< half-edges with sign +1, in order
  ///@{
  /// The transversals at the run's start and end.
  Transversal atStart, atEnd;
  ///@}
  /// Affine-matrix variant (Kuriyama 1996, sec. 5.2.1): M-+(u) = c-+ (u^2 - Delta u) + l-+(u) I,
  /// shared by both faces. Off (parallel sweeps with influence weights, Kuriyama 1996, sec. 5.2.1)
  /// unless set by fairRunSweeps().
  bool affine = false;
  Eigen::Matrix3d cStart = Eigen::Matrix3d::Zero();  ///< c_- (start transversal), row j col k
  Eigen::Matrix3d cEnd = Eigen::Matrix3d::Zero();    ///< c_+ (end transversal)
  /// Parameter length of the run, tEnd - tStart.
  double delta() const { return tEnd - tStart; }
};

/// One side of a face: the fraction [rho0, rho1] of a run, traversed forward (increasing t)
/// or backward. rho0 = 0 and rho1 = 1 for a plain side; a proper sub-range on the stem side of
/// a T-junction (rule b) and for the halves of a two-curve region (rule d).
struct FaceSide {
  int run = -1;          ///< -1: the virtual side of an open region (rule (c))
  ///@{
  /// Fraction of the run the side covers, rho0 < rho1.
  double rho0 = 0.0, rho1 = 1.0;
  ///@}
  bool forward = true;  ///< the side runs with increasing t
  int startVertex = -1;  ///< network vertex at the side's start, -1 for a two-curve midpoint
  double delta = 0.0;    ///< parameter length Delta of the side
};

/// A face of the network: a cycle of half-edges filled by one patch.
struct Face {
  std::vector<int> halfEdges;  ///< the traced cycle, CCW seen from the outward normal
  std::vector<FaceSide> sides; ///< the patch sides (>= 3)
  bool twoCurveRegion = false; ///< built from 2 sides by rule (d)
  bool openRegion = false;     ///< rule (c): the last side is virtual, halfEdges is a chain
};

/// A traced orbit of `next` that ends at a free end or a dead end: an open region left empty
/// (see CurveNetworkOptions::fillOpenRegions), reported with its curves and where it ends.
struct OpenChain {
  std::vector<int> halfEdges;  ///< the chain's half-edges, in order
  std::string description;  ///< its curves and where it ends, for the report
};

/// A curve network after intersection, correction and topology inference.
struct CurveNetwork {
  std::vector<NetworkCurve> curves;         ///< corrected curves
  std::vector<std::string> curveNames;  ///< the curves' names
  std::vector<double> influence;  ///< the curves' influence weights
  std::vector<std::optional<Plane>> planes;  ///< the curves' drawing planes (none: not planar)
  std::vector<NetworkVertex> vertices;  ///< crossings, junctions and free ends
  std::vector<HalfEdge> halfEdges;  ///< the curve pieces between vertices, both directions
  std::vector<Run> runs;  ///< maximal pieces of one curve between through-vertices
  std::vector<Face> faces;  ///< the traced faces, one patch each
  std::vector<OpenChain> openChains;  ///< open regions left empty
  std::vector<std::string> notes;           ///< non-fatal findings, human readable
  double tolerance = 0.0;                   ///< tau actually used
  double scale = 1.0;                       ///< bounding-box diagonal L
  double correctionResidual = 0.0;          ///< max |K_c(t_c) - X_v| after correction

  /// Edges (pairs of twin half-edges) that are not dangling.
  int edgeCount() const;
};

/// Builds the network: curves from the description, pairwise intersections with tolerance tau
/// (closest points of the two curves, refined by Newton, projected onto the drawing planes;
/// an open end within tau of a curve is a T-junction), clusters of >= 3 curves into multiple
/// points, curve correction by minimum-norm displacement splines that stay in the drawing
/// planes, half-edges, vertex normals N.1-N.4 with propagation, deterministic face tracing
/// (largest left turn), runs and face sides with the T-junction and two-curve rules, and on
/// request open regions closed by a virtual side (rule (c)).
/// Non-fatal findings go to CurveNetwork::notes: near misses (two curves within 3 tau that do
/// not meet), open regions left empty, orientations taken from the hint, ambiguous turns.
/// @see Kuriyama 1996, secs. 5.3.3, 5.3.4 (IF3D a.1-a.4, L.1-L.8, N.1-N.4), sec. 5.2.4.
/// @throws CurveInputError for a curve that cannot be built; CurveNetworkError naming the
///   curve(s) and the place for: a curve meeting no other curve (with its nearest miss), two
///   curves that are tangent or nearly coincident, a correction that cannot meet the
///   intersections, a face with one side.
CurveNetwork buildCurveNetwork(const CurveNetworkDescription& description,
                               const CurveNetworkOptions& options = {});

/// "name" or "curve <index>", for messages.
std::string curveLabel(const CurveNetwork& network, int curve);

}  // namespace ffdkit::geometry::curvenet
