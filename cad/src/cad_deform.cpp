// Deforming B-rep models by an FFD lattice: exact composition (cell by cell), an approximation on
// the same parameters where that is not possible, or pole moving; every vertex, edge and face
// through one BRepTools_Modification so shared boundaries stay shared.
#include "ffdkit/cad/cad_deform.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <Precision.hxx>
#include <BRepTools_Modification.hxx>
#include <BRepTools_Modifier.hxx>
#include <BRep_Tool.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierCurve.hxx>
#include <Geom_BezierSurface.hxx>
#include <Geom_Line.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <Geom2d_Curve.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListIteratorOfListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>

#include "cad_model_data.h"
#include "ffd_map.h"
#include "geometry_fit.h"
#include "occt_points.h"
#include "piecewise_composition.h"

namespace ffdkit::cad {

namespace {

using detail::toEigen;
using detail::toPnt;

Handle(Geom_BSplineSurface) asBSpline(const Handle(Geom_Surface)& surface, const std::string& where) {
  if (auto trimmed = Handle(Geom_RectangularTrimmedSurface)::DownCast(surface)) return asBSpline(trimmed->BasisSurface(), where);
  Handle(Geom_BSplineSurface) bs;
  if (auto b = Handle(Geom_BSplineSurface)::DownCast(surface))
    bs = Handle(Geom_BSplineSurface)::DownCast(b->Copy());
  else if (auto bezier = Handle(Geom_BezierSurface)::DownCast(surface))
    bs = GeomConvert::SurfaceToBSplineSurface(bezier);
  else
    throw CadError(where + ": a " + std::string(surface->DynamicType()->Name()) + " is left after the NURBS conversion");
  if (bs->IsUPeriodic()) bs->SetUNotPeriodic();
  if (bs->IsVPeriodic()) bs->SetVNotPeriodic();
  // Unclamped ends (a multiplicity below degree + 1): clamp them where the surface starts and ends.
  if (bs->UMultiplicity(1) != bs->UDegree() + 1 || bs->UMultiplicity(bs->NbUKnots()) != bs->UDegree() + 1 ||
      bs->VMultiplicity(1) != bs->VDegree() + 1 || bs->VMultiplicity(bs->NbVKnots()) != bs->VDegree() + 1) {
    Standard_Real u0, u1, v0, v1;
    bs->Bounds(u0, u1, v0, v1);
    bs->Segment(u0, u1, v0, v1);
  }
  return bs;
}

Handle(Geom_BSplineCurve) asBSpline(const Handle(Geom_Curve)& curve, double first, double last, const std::string& where) {
  if (auto trimmed = Handle(Geom_TrimmedCurve)::DownCast(curve)) return asBSpline(trimmed->BasisCurve(), first, last, where);
  Handle(Geom_BSplineCurve) bs;
  if (auto b = Handle(Geom_BSplineCurve)::DownCast(curve)) {
    bs = Handle(Geom_BSplineCurve)::DownCast(b->Copy());
  } else if (auto bezier = Handle(Geom_BezierCurve)::DownCast(curve)) {
    bs = GeomConvert::CurveToBSplineCurve(bezier);
  } else if (Handle(Geom_Line)::DownCast(curve)) {
    // Degree 1 on [first, last]: the line's own parameter, so the edge's range stays valid.
    TColgp_Array1OfPnt poles(1, 2);
    poles(1) = curve->Value(first);
    poles(2) = curve->Value(last);
    TColStd_Array1OfReal knots(1, 2);
    knots(1) = first;
    knots(2) = last;
    TColStd_Array1OfInteger mults(1, 2);
    mults.Init(2);
    bs = new Geom_BSplineCurve(poles, knots, mults, 1);
  } else {
    throw CadError(where + ": a " + std::string(curve->DynamicType()->Name()) + " is left after the NURBS conversion");
  }
  if (bs->IsPeriodic()) bs->SetNotPeriodic();
  if (bs->Multiplicity(1) != bs->Degree() + 1 || bs->Multiplicity(bs->NbKnots()) != bs->Degree() + 1)
    bs->Segment(bs->FirstParameter(), bs->LastParameter());
  return bs;
}

void checkClamped(const TColStd_Array1OfInteger& mults, int degree, const std::string& where) {
  if (mults(mults.Lower()) != degree + 1 || mults(mults.Upper()) != degree + 1)
    throw CadError(where + ": an unclamped B-spline (end knot multiplicity below degree + 1) is not supported");
}

/// Where a face or edge lies relative to the lattice (sampled: 17 x 17 per face inside its trim,
/// 33 points per edge).
enum class Region { Inside, Outside, Across };

const char* policyName(ffd::OutsidePolicy::Kind kind) {
  switch (kind) {
    case ffd::OutsidePolicy::Kind::Identity: return "Identity";
    case ffd::OutsidePolicy::Kind::ClampEdge: return "ClampEdge";
    case ffd::OutsidePolicy::Kind::Extrapolate: return "Extrapolate";
    case ffd::OutsidePolicy::Kind::Falloff: return "Falloff";
  }
  return "?";
}

std::string formatNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

/// The deformation of one part's surfaces, curves and points (BRepTools_Modifier calls it for every
/// face, edge and vertex once; shared ones are shared in the result).
class FfdModification : public BRepTools_Modification {
 public:
  FfdModification(const FfdMap& map, const gp_Trsf& placement, const TopoDS_Shape& shape, const std::string& part,
                  CadDeformReport& report)
      : map_(map), placement_(placement), part_(part), report_(report) {
    TopExp::MapShapes(shape, TopAbs_FACE, faces_);
    TopExp::MapShapes(shape, TopAbs_EDGE, edges_);
  }

  /// True when a surface or curve of the part was approximated (its tolerances need settling).
  bool approximated() const { return approximated_; }

  Standard_Boolean NewSurface(const TopoDS_Face& face, Handle(Geom_Surface)& surface, TopLoc_Location& location,
                              Standard_Real& tolerance, Standard_Boolean& revWires, Standard_Boolean& revFace) override {
    surface = BRep_Tool::Surface(face, location);
    if (surface.IsNull()) return Standard_False;
    const std::string where = "part '" + part_ + "', face " + std::to_string(faces_.FindIndex(face));
    Handle(Geom_BSplineSurface) bs = asBSpline(surface, where);
    bs->Transform(placement_ * location.Transformation());
    double error = 0.0;
    Handle(Geom_BSplineSurface) moved = map_.options().method == CadMethod::Exact ? deformSurface(face, bs, where, error)
                                                                                  : movePoles(bs);
    if (!location.IsIdentity()) moved->Transform(location.Transformation().Inverted());
    surface = moved;
    tolerance = BRep_Tool::Tolerance(face) * std::max(1.0, map_.lipschitz()) + error;
    revWires = Standard_False;
    revFace = Standard_False;
    return Standard_True;
  }

  Standard_Boolean NewCurve(const TopoDS_Edge& edge, Handle(Geom_Curve)& curve, TopLoc_Location& location,
                            Standard_Real& tolerance) override {
    Standard_Real first = 0.0, last = 0.0;
    curve = BRep_Tool::Curve(edge, location, first, last);
    if (curve.IsNull()) return Standard_False;
    const std::string where = "part '" + part_ + "', edge " + std::to_string(edges_.FindIndex(edge));
    Handle(Geom_BSplineCurve) bs = asBSpline(curve, first, last, where);
    bs->Transform(placement_ * location.Transformation());
    double error = 0.0;
    Handle(Geom_BSplineCurve) moved = map_.options().method == CadMethod::Exact
                                          ? deformCurve(edge, bs, first, last, where, error)
                                          : movePoles(bs);
    if (!location.IsIdentity()) moved->Transform(location.Transformation().Inverted());
    curve = moved;
    tolerance = BRep_Tool::Tolerance(edge) * std::max(1.0, map_.lipschitz()) + error;
    return Standard_True;
  }

  Standard_Boolean NewPoint(const TopoDS_Vertex& vertex, gp_Pnt& point, Standard_Real& tolerance) override {
    const Eigen::Vector3d world = toEigen(BRep_Tool::Pnt(vertex).Transformed(placement_));
    if (map_.options().method == CadMethod::Exact && !map_.options().approximate && map_.polynomial() &&
        !map_.extrapolates() && !map_.inside(world))
      throw outsideError("part '" + part_ + "', a vertex", world);
    point = toPnt(map_.point(world));
    tolerance = BRep_Tool::Tolerance(vertex) * std::max(1.0, map_.lipschitz());
    return Standard_True;
  }

  Standard_Boolean NewCurve2d(const TopoDS_Edge& edge, const TopoDS_Face& face, const TopoDS_Edge&, const TopoDS_Face&,
                              Handle(Geom2d_Curve)& curve, Standard_Real& tolerance) override {
    // The surfaces keep their parameters (same knots, or a fit on the same parameters), so every
    // p-curve stays as it is.
    Standard_Real first = 0.0, last = 0.0;
    const Handle(Geom2d_Curve) original = BRep_Tool::CurveOnSurface(edge, face, first, last);
    if (original.IsNull()) return Standard_False;
    curve = Handle(Geom2d_Curve)::DownCast(original->Copy());
    tolerance = BRep_Tool::Tolerance(edge) * std::max(1.0, map_.lipschitz());
    return Standard_True;
  }

  Standard_Boolean NewParameter(const TopoDS_Vertex&, const TopoDS_Edge&, Standard_Real&, Standard_Real&) override {
    return Standard_False;  // the curves keep their parameters
  }

  GeomAbs_Shape Continuity(const TopoDS_Edge& edge, const TopoDS_Face& f1, const TopoDS_Face& f2, const TopoDS_Edge&,
                           const TopoDS_Face&, const TopoDS_Face&) override {
    return BRep_Tool::Continuity(edge, f1, f2);  // a smooth map keeps a smooth join smooth
  }

 private:
  CadError outsideError(const std::string& where, const Eigen::Vector3d& world) const {
    const Eigen::Vector3d uvw = map_.parameters(world);
    return CadError(where + " lies outside the lattice (lattice parameters (" + std::to_string(uvw.x()) + ", " +
                    std::to_string(uvw.y()) + ", " + std::to_string(uvw.z()) + ")): with the " +
                    policyName(map_.lattice().outsidePolicy().kind) +
                    " outside policy the FFD is not one polynomial there; enlarge the lattice, use the Extrapolate "
                    "policy or allow the approximation");
  }

  /// Where the points are relative to the lattice (the Extrapolate policy: always Inside).
  Region regionOf(const std::vector<Eigen::Vector3d>& points) const {
    if (map_.extrapolates()) return Region::Inside;
    int inside = 0;
    for (const Eigen::Vector3d& p : points) inside += map_.inside(p) ? 1 : 0;
    return inside == static_cast<int>(points.size()) ? Region::Inside : inside == 0 ? Region::Outside : Region::Across;
  }

  /// A 17 x 17 grid of the face's parameters classified against its boundary (its surface may
  /// extend beyond it: that part is trimmed away).
  std::vector<Eigen::Vector3d> samplesOf(const TopoDS_Face& face) const {
    Standard_Real u0, u1, v0, v1;
    BRepTools::UVBounds(face, u0, u1, v0, v1);
    BRepAdaptor_Surface surface(face, false);
    BRepTopAdaptor_FClass2d classifier(face, Precision::PConfusion());
    std::vector<Eigen::Vector3d> points;
    const int n = 16;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) {
        const gp_Pnt2d uv(u0 + (u1 - u0) * i / n, v0 + (v1 - v0) * j / n);
        if (classifier.Perform(uv) == TopAbs_OUT) continue;
        points.push_back(toEigen(surface.Value(uv.X(), uv.Y()).Transformed(placement_)));
      }
    return points;
  }

  /// 33 points of the edge's range.
  std::vector<Eigen::Vector3d> samplesOf(const TopoDS_Edge& edge) const {
    BRepAdaptor_Curve curve(edge);
    std::vector<Eigen::Vector3d> points;
    const int n = 32;
    for (int i = 0; i <= n; ++i) {
      const double t = curve.FirstParameter() + (curve.LastParameter() - curve.FirstParameter()) * i / n;
      points.push_back(toEigen(curve.Value(t).Transformed(placement_)));
    }
    return points;
  }

  /// Why the FFD of geometry of degree `degree` in the region cannot be composed exactly (empty:
  /// it can, or, for the Identity policy wholly outside, it is the identity).
  std::string whyNotExact(Region region, int degree, const std::vector<Eigen::Vector3d>& samples,
                          const std::string& where) const {
    if (!map_.polynomial())
      return "the lattice's rest shape is not a box (a cylindrical lattice): its FFD is not a polynomial of world "
             "coordinates";
    const auto policy = map_.lattice().outsidePolicy().kind;
    if (region == Region::Across || (region == Region::Outside && policy != ffd::OutsidePolicy::Kind::Identity)) {
      if (!map_.options().approximate)
        for (const Eigen::Vector3d& p : samples)
          if (!map_.inside(p)) throw outsideError(where, p);
      return std::string(region == Region::Across ? "it crosses the lattice's boundary" : "it lies outside the lattice") +
             ", where the " + policyName(policy) + " outside policy is not the lattice's polynomial";
    }
    if (degree > map_.options().maxDegree)
      return "the exact composition has degree " + std::to_string(degree) + ", above the limit of " +
             std::to_string(map_.options().maxDegree);
    return {};
  }

  /// The approximation is allowed, or a CadError saying why the geometry is not exact.
  void requireApproximation(const std::string& where, const std::string& why) const {
    if (!map_.options().approximate)
      throw CadError(where + " cannot be deformed exactly: " + why +
                     " (CadDeformOptions::approximate is off; a lattice of fewer control points lowers the degree)");
  }

  void noteApproximation(const std::string& where, const std::string& why, double error, bool face) {
    if (error > map_.tolerance())
      throw CadError(where + ": approximating its deformation (" + why + ") reached a deviation of " +
                     formatNumber(error) + ", above the tolerance of " + formatNumber(map_.tolerance()) +
                     " (a larger tolerance, or a lattice that bends the part less, lets it through)");
    report_.approximations.push_back(where + ": " + why + "; approximated within " + formatNumber(error));
    report_.approximationError = std::max(report_.approximationError, error);
    (face ? report_.approximatedFaces : report_.approximatedEdges) += 1;
    approximated_ = true;
  }

  /// The degree of an approximation: at least 5 (or the original's), at most the limit.
  int fitDegree(int original) const { return std::min(map_.options().maxDegree, std::max(5, original)); }

  Handle(Geom_BSplineSurface) deformSurface(const TopoDS_Face& face, const Handle(Geom_BSplineSurface)& bs,
                                            const std::string& where, double& error) {
    const std::vector<Eigen::Vector3d> samples = samplesOf(face);
    const Region region = regionOf(samples);
    const int d = map_.totalDegree();
    std::string why = whyNotExact(region, d * std::max(bs->UDegree(), bs->VDegree()), samples, where);
    if (why.empty() && region == Region::Outside) {  // the Identity policy: the FFD leaves it where it is
      noteDegree(std::max(bs->UDegree(), bs->VDegree()));
      return bs;
    }
    if (why.empty()) {
      TColStd_Array1OfInteger um(1, bs->NbUKnots()), vm(1, bs->NbVKnots());
      bs->UMultiplicities(um);
      bs->VMultiplicities(vm);
      checkClamped(um, bs->UDegree(), where);
      checkClamped(vm, bs->VDegree(), where);
      const ExactSurface exact = composeSurfaceExactly(map_, bs);
      if (exact.surface) {
        noteDegree(std::max(exact.surface->UDegree(), exact.surface->VDegree()));
        return exact.surface;
      }
      why = exact.whyNot;
    }
    requireApproximation(where, why);
    Standard_Real u0, u1, v0, v1, su0, su1, sv0, sv1;
    BRepTools::UVBounds(face, u0, u1, v0, v1);
    bs->Bounds(su0, su1, sv0, sv1);
    u0 = std::max(u0, su0);
    u1 = std::min(u1, su1);
    v0 = std::max(v0, sv0);
    v1 = std::min(v1, sv1);
    SurfaceCrossings kinks;
    const Planes knotPlanes{map_.knotPlanes(0), map_.knotPlanes(1), map_.knotPlanes(2)};
    if (map_.polynomial())
      kinks = parameterLineCrossings(map_, bs, region == Region::Inside ? knotPlanes : map_.kinkPlanes());
    const SurfaceFit fit = fitSurface(map_, bs, u0, u1, v0, v1, fitDegree(bs->UDegree()), fitDegree(bs->VDegree()),
                                      map_.tolerance(), region == Region::Inside, kinks.u, kinks.v);
    noteApproximation(where, why, fit.error, true);
    noteDegree(std::max(fit.surface->UDegree(), fit.surface->VDegree()));
    error = fit.error;
    return fit.surface;
  }

  Handle(Geom_BSplineCurve) deformCurve(const TopoDS_Edge& edge, const Handle(Geom_BSplineCurve)& bs, double first,
                                        double last, const std::string& where, double& error) {
    const std::vector<Eigen::Vector3d> samples = samplesOf(edge);
    const Region region = regionOf(samples);
    std::string why = whyNotExact(region, map_.totalDegree() * bs->Degree(), samples, where);
    if (why.empty() && region == Region::Outside) {
      noteDegree(bs->Degree());
      return bs;
    }
    if (why.empty()) {
      TColStd_Array1OfInteger mults(1, bs->NbKnots());
      bs->Multiplicities(mults);
      checkClamped(mults, bs->Degree(), where);
      const ExactCurve exact = composeCurveExactly(map_, bs);
      if (exact.curve) {
        noteDegree(exact.curve->Degree());
        return exact.curve;
      }
      why = exact.whyNot;
    }
    requireApproximation(where, why);
    const std::vector<double> kinks = map_.polynomial() ? curveCrossings(map_, bs, map_.kinkPlanes()) : std::vector<double>{};
    const CurveFit fit = fitCurve(map_, bs, std::max(first, bs->FirstParameter()), std::min(last, bs->LastParameter()),
                                  fitDegree(bs->Degree()), map_.tolerance(), kinks);
    noteApproximation(where, why, fit.error, false);
    noteDegree(fit.curve->Degree());
    error = fit.error;
    return fit.curve;
  }

  void noteDegree(int degree) { report_.maxDegree = std::max(report_.maxDegree, degree); }

  Handle(Geom_BSplineSurface) movePoles(const Handle(Geom_BSplineSurface)& bs) {
    noteDegree(std::max(bs->UDegree(), bs->VDegree()));
    Eigen::MatrixX3d poles(static_cast<Eigen::Index>(bs->NbUPoles()) * bs->NbVPoles(), 3);
    Eigen::Index row = 0;
    for (Standard_Integer i = 1; i <= bs->NbUPoles(); ++i)
      for (Standard_Integer j = 1; j <= bs->NbVPoles(); ++j) poles.row(row++) = toEigen(bs->Pole(i, j)).transpose();
    const Eigen::MatrixX3d moved = map_.points(poles);
    row = 0;
    for (Standard_Integer i = 1; i <= bs->NbUPoles(); ++i)
      for (Standard_Integer j = 1; j <= bs->NbVPoles(); ++j, ++row)
        bs->SetPole(i, j, toPnt(moved.row(row).transpose()), bs->Weight(i, j));
    return bs;
  }

  Handle(Geom_BSplineCurve) movePoles(const Handle(Geom_BSplineCurve)& bs) {
    noteDegree(bs->Degree());
    Eigen::MatrixX3d poles(bs->NbPoles(), 3);
    for (Standard_Integer i = 1; i <= bs->NbPoles(); ++i) poles.row(i - 1) = toEigen(bs->Pole(i)).transpose();
    const Eigen::MatrixX3d moved = map_.points(poles);
    for (Standard_Integer i = 1; i <= bs->NbPoles(); ++i) bs->SetPole(i, toPnt(moved.row(i - 1).transpose()), bs->Weight(i));
    return bs;
  }

  const FfdMap& map_;
  gp_Trsf placement_;
  std::string part_;
  CadDeformReport& report_;
  TopTools_IndexedMapOfShape faces_;
  TopTools_IndexedMapOfShape edges_;
  bool approximated_ = false;
};

/// True when a sub-shape below the root carries a placement of its own (the modifier's frames
/// would then differ between its passes).
bool hasInnerLocations(const TopoDS_Shape& shape) {
  for (TopoDS_Iterator it(shape, false, false); it.More(); it.Next())
    if (!it.Value().Location().IsIdentity() || hasInnerLocations(it.Value())) return true;
  return false;
}

/// The edge as it is to be read on the face: once, or for a seam (an edge on a closed face, with
/// a p-curve on each side of the face's parameter domain) twice, forward and reversed, so that
/// both p-curves are measured (BRep_Tool picks the p-curve by the edge's orientation).
std::vector<TopoDS_Edge> curvesOnFace(const TopoDS_Edge& edge, const TopoDS_Face& face) {
  if (!BRep_Tool::IsClosed(edge, face)) return {edge};
  return {TopoDS::Edge(edge.Oriented(TopAbs_FORWARD)), TopoDS::Edge(edge.Oriented(TopAbs_REVERSED))};
}

/// After an approximation, an edge's curve and its curves on its faces no longer agree to
/// rounding. Each edge's tolerance grows to cover them: to the bound the fits give (the edge's
/// curve is within its tolerance of the FFD of the original edge, which lay on the original face;
/// the face's surface within the face's tolerance of the FFD of that face: their sum, as
/// NewSurface and NewCurve set them, bounds the gap), and to at least 1.5 times the largest distance
/// measured between them (65 points per curve on the face, both p-curves of a seam). Sampling alone
/// is not enough: between 33 samples the gap to an approximated face of the bent pipe or the bottle
/// reached more than twice the tolerance set from them, and BRepCheck_Analyzer rejected the face. Each vertex's tolerance
/// then grows to cover its edges and the ends of their curves.
void settleTolerances(const TopoDS_Shape& shape) {
  BRep_Builder builder;
  TopTools_IndexedDataMapOfShapeListOfShape facesOfEdge;
  TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, facesOfEdge);
  TopTools_IndexedDataMapOfShapeListOfShape edgesOfVertex;
  TopExp::MapShapesAndAncestors(shape, TopAbs_VERTEX, TopAbs_EDGE, edgesOfVertex);
  std::vector<double> vertexTolerance(edgesOfVertex.Extent() + 1, 0.0);
  for (Standard_Integer e = 1; e <= facesOfEdge.Extent(); ++e) {
    const TopoDS_Edge& edge = TopoDS::Edge(facesOfEdge.FindKey(e));
    const bool degenerated = BRep_Tool::Degenerated(edge);
    double gap = 0.0, faceTolerance = 0.0;
    std::vector<gp_Pnt> ends;
    TopoDS_Vertex first, last;
    TopExp::Vertices(edge, first, last);
    Standard_Real t0 = 0.0, t1 = 0.0;
    BRep_Tool::Range(edge, t0, t1);
    std::optional<BRepAdaptor_Curve> curve;
    if (!degenerated && BRep_Tool::IsGeometric(edge)) curve.emplace(edge);
    for (TopTools_ListIteratorOfListOfShape f(facesOfEdge(e)); f.More(); f.Next())
      for (const TopoDS_Edge& side : curvesOnFace(edge, TopoDS::Face(f.Value()))) {
        faceTolerance = std::max(faceTolerance, BRep_Tool::Tolerance(TopoDS::Face(f.Value())));
        BRepAdaptor_Curve onFace(side, TopoDS::Face(f.Value()));
        for (int k = 0; k <= 64; ++k) {
          const double t = t0 + (t1 - t0) * k / 64;
          const gp_Pnt p = onFace.Value(t);
          if (curve) gap = std::max(gap, curve->Value(t).Distance(p));
          if (degenerated && !first.IsNull()) gap = std::max(gap, BRep_Tool::Pnt(first).Distance(p));
        }
        ends.push_back(onFace.Value(t0));
        ends.push_back(onFace.Value(t1));
      }
    if (curve) {
      ends.push_back(curve->Value(t0));
      ends.push_back(curve->Value(t1));
    }
    const double bound = degenerated ? BRep_Tool::Tolerance(edge) : BRep_Tool::Tolerance(edge) + faceTolerance;
    const double tolerance = std::max(bound, 1.5 * gap);
    builder.UpdateEdge(edge, tolerance);
    for (const TopoDS_Vertex& vertex : {first, last}) {
      if (vertex.IsNull()) continue;
      const Standard_Integer v = edgesOfVertex.FindIndex(vertex);
      double reach = tolerance;
      for (std::size_t i = 0; i < ends.size(); ++i)
        if ((i % 2 == 0) == (vertex.IsSame(first))) reach = std::max(reach, 1.5 * BRep_Tool::Pnt(vertex).Distance(ends[i]));
      vertexTolerance[v] = std::max(vertexTolerance[v], reach);
    }
  }
  for (Standard_Integer v = 1; v <= edgesOfVertex.Extent(); ++v) {
    const TopoDS_Vertex& vertex = TopoDS::Vertex(edgesOfVertex.FindKey(v));
    if (vertexTolerance[v] > BRep_Tool::Tolerance(vertex)) builder.UpdateVertex(vertex, vertexTolerance[v]);
  }
}

/// Max |S'(s,t) - X(S(s,t))| over a grid per face (the points inside its trim), and max distance
/// between each edge's 3D curve and its curves on the faces that share it.
void measure(const TopoDS_Shape& original, const gp_Trsf& placement, const TopoDS_Shape& deformed,
             const BRepTools_Modifier& modifier, const FfdMap& map, int samples, CadDeformReport& report) {
  for (TopExp_Explorer it(original, TopAbs_FACE); it.More(); it.Next()) {
    const TopoDS_Face& face = TopoDS::Face(it.Current());
    const TopoDS_Face moved = TopoDS::Face(modifier.ModifiedShape(face));
    Standard_Real u0, u1, v0, v1;
    BRepTools::UVBounds(face, u0, u1, v0, v1);
    BRepAdaptor_Surface before(face, false);
    BRepAdaptor_Surface after(moved, false);
    BRepTopAdaptor_FClass2d classifier(face, Precision::PConfusion());
    std::vector<Eigen::Vector3d> from, to;
    for (int i = 0; i < samples; ++i)
      for (int j = 0; j < samples; ++j) {
        const double u = u0 + (u1 - u0) * i / std::max(1, samples - 1);
        const double v = v0 + (v1 - v0) * j / std::max(1, samples - 1);
        if (classifier.Perform(gp_Pnt2d(u, v)) == TopAbs_OUT) continue;  // trimmed away
        from.push_back(toEigen(before.Value(u, v).Transformed(placement)));
        to.push_back(toEigen(after.Value(u, v)));
      }
    Eigen::MatrixX3d world(static_cast<Eigen::Index>(from.size()), 3);
    for (std::size_t k = 0; k < from.size(); ++k) world.row(static_cast<Eigen::Index>(k)) = from[k].transpose();
    const Eigen::MatrixX3d expected = map.points(world);
    for (std::size_t k = 0; k < to.size(); ++k)
      report.maxDeviation = std::max(report.maxDeviation, (to[k] - expected.row(static_cast<Eigen::Index>(k)).transpose()).norm());
  }
  TopTools_IndexedDataMapOfShapeListOfShape facesOfEdge;
  TopExp::MapShapesAndAncestors(deformed, TopAbs_EDGE, TopAbs_FACE, facesOfEdge);
  for (Standard_Integer e = 1; e <= facesOfEdge.Extent(); ++e) {
    const TopoDS_Edge& edge = TopoDS::Edge(facesOfEdge.FindKey(e));
    if (BRep_Tool::Degenerated(edge) || !BRep_Tool::IsGeometric(edge)) continue;
    BRepAdaptor_Curve curve(edge);
    for (TopTools_ListIteratorOfListOfShape f(facesOfEdge(e)); f.More(); f.Next())
      for (const TopoDS_Edge& side : curvesOnFace(edge, TopoDS::Face(f.Value()))) {
        BRepAdaptor_Curve onFace(side, TopoDS::Face(f.Value()));
        for (int k = 0; k < samples; ++k) {
          const double t = curve.FirstParameter() + (curve.LastParameter() - curve.FirstParameter()) * k / std::max(1, samples - 1);
          report.maxGap = std::max(report.maxGap, curve.Value(t).Distance(onFace.Value(t)));
        }
      }
  }
}

}  // namespace

CadDeformResult deformCad(const CadModel& model, const ffd::Lattice& lattice, const CadDeformOptions& options) {
  if (options.samples < 0) throw CadError("samples must be >= 0, got " + std::to_string(options.samples));
  const FfdMap map(lattice, options, model.bounds().isEmpty() ? 1.0 : model.bounds().diagonal().norm());
  CadDeformResult result;
  double seconds = 0.0;
  for (const auto& part : model.data().parts) {
    const std::string context = "deforming part '" + part.name + "'";
    guardOcct(context, [&] {
      const auto start = std::chrono::steady_clock::now();
      const gp_Trsf placement = part.shape.Location().Transformation();
      const TopoDS_Shape local = part.shape.Located(TopLoc_Location());
      BRepBuilderAPI_NurbsConvert convert(local, true);
      const TopoDS_Shape nurbs = convert.Shape();
      if (hasInnerLocations(nurbs))
        throw CadError(context + ": sub-shapes with placements of their own are not supported yet");
      Handle(FfdModification) modification = new FfdModification(map, placement, nurbs, part.name, result.report);
      BRepTools_Modifier modifier(nurbs);
      modifier.Perform(modification);
      if (!modifier.IsDone()) throw CadError(context + ": OpenCASCADE's modifier did not complete");
      const TopoDS_Shape deformed = modifier.ModifiedShape(nurbs);
      if (modification->approximated()) settleTolerances(deformed);
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      result.model.data().parts.push_back({part.name, deformed});
      TopTools_IndexedMapOfShape faces, edges;
      TopExp::MapShapes(nurbs, TopAbs_FACE, faces);
      TopExp::MapShapes(nurbs, TopAbs_EDGE, edges);
      result.report.faces += faces.Extent();
      result.report.edges += edges.Extent();
      if (options.samples > 0) measure(nurbs, placement, deformed, modifier, map, options.samples, result.report);
    });
  }
  result.report.seconds = seconds;
  if (!result.report.approximations.empty()) result.report.tolerance = map.tolerance();
  return result;
}

}  // namespace ffdkit::cad
