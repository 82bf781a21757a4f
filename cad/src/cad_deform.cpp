// Deforming B-rep models by an FFD lattice: exact composition (Bernstein lattices) or pole moving,
// every vertex, edge and face through one BRepTools_Modification so shared boundaries stay shared.
#include "ffdkit/cad/cad_deform.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepTools.hxx>
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
#include "ffdkit/cad/bernstein_composition.h"

namespace ffdkit::cad {

namespace {

Eigen::Vector3d toEigen(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }
gp_Pnt toPnt(const Eigen::Vector3d& p) { return gp_Pnt(p.x(), p.y(), p.z()); }

/// The lattice's FFD as a map of world points, and what the CAD deformation needs of it.
class FfdMap {
 public:
  FfdMap(const ffd::Lattice& lattice, const CadDeformOptions& options) : lattice_(lattice), options_(options) {
    if (!lattice.restIsAffine())
      throw CadError("CAD deformation needs a lattice whose rest shape is a box (an affine rest map)");
    const auto kind = lattice.outsidePolicy().kind;
    if (kind != ffd::OutsidePolicy::Kind::Identity && kind != ffd::OutsidePolicy::Kind::Extrapolate)
      throw CadError("CAD deformation supports the Identity and Extrapolate outside policies (ClampEdge and Falloff "
                     "are not polynomial outside the lattice; approximating them is not implemented)");
    if (options.method == CadMethod::Exact) {
      volume_ = BernsteinVolume::fromLattice(lattice);
      if (options.maxDegree < 1 || options.maxDegree > Geom_BSplineSurface::MaxDegree())
        throw CadError("maxDegree must be in [1, " + std::to_string(Geom_BSplineSurface::MaxDegree()) + "], got " +
                       std::to_string(options.maxDegree));
    }
    Eigen::Affine3d toLocalParameter = Eigen::Affine3d::Identity();
    toLocalParameter.linear() = lattice.restAffineLinear().inverse();
    toLocalParameter.translation() = -(toLocalParameter.linear() * lattice.restAffineOffset());
    toParameter_ = toLocalParameter * lattice.frame().inverse();
    lipschitz_ = lipschitzBound();
  }

  const CadDeformOptions& options() const { return options_; }
  const BernsteinVolume& volume() const { return *volume_; }
  bool extrapolates() const { return lattice_.outsidePolicy().kind == ffd::OutsidePolicy::Kind::Extrapolate; }
  /// A bound of |dX| / |dq| in the lattice (tolerances of moved edges and vertices scale by it).
  double lipschitz() const { return lipschitz_; }

  /// (u, v, w) of a world point.
  Eigen::Vector3d parameters(const Eigen::Vector3d& world) const { return toParameter_ * world; }
  bool inside(const Eigen::Vector3d& world) const {
    const Eigen::Vector3d uvw = parameters(world);
    const double eps = 1e-9;
    return (uvw.array() >= lattice_.parameterMin().array() - eps).all() &&
           (uvw.array() <= lattice_.parameterMax().array() + eps).all();
  }

  /// X(q) as the FFD engine evaluates it (Lattice::evaluate), the outside policy applied.
  Eigen::Vector3d point(const Eigen::Vector3d& world) const {
    if (!extrapolates() && !inside(world)) return world;
    return lattice_.frame() * lattice_.evaluate(parameters(world));
  }

 private:
  double lipschitzBound() const {
    // |J v| <= |R|_2 sqrt(sum_a c_a^2) |v|, R = d(uvw)/dq, c_a a bound of |dX/du_a| (the
    // derivative's control net: degree times the largest difference of neighbours along a).
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    const Eigen::Vector3i n = lattice_.counts();
    const Eigen::MatrixX3d world = (lattice_.frame() * lattice_.controlPoints().transpose()).transpose();
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i) {
          const Eigen::Index at = lattice_.index(i, j, k);
          if (i + 1 < n[0]) c[0] = std::max(c[0], (world.row(lattice_.index(i + 1, j, k)) - world.row(at)).norm());
          if (j + 1 < n[1]) c[1] = std::max(c[1], (world.row(lattice_.index(i, j + 1, k)) - world.row(at)).norm());
          if (k + 1 < n[2]) c[2] = std::max(c[2], (world.row(lattice_.index(i, j, k + 1)) - world.row(at)).norm());
        }
    for (int a = 0; a < 3; ++a) {
      const auto& axis = lattice_.axis(a);
      const double span = axis.domainMax() - axis.domainMin();
      // A B-spline's derivative net divides by knot spans; degree / (smallest cell) bounds it.
      double smallest = span;
      for (int cell = 0; cell < axis.cellCount(); ++cell) smallest = std::min(smallest, axis.cellMax(cell) - axis.cellMin(cell));
      c[a] *= axis.degree() / smallest;
    }
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(toParameter_.linear());
    return svd.singularValues()[0] * c.norm();
  }

  const ffd::Lattice& lattice_;
  CadDeformOptions options_;
  std::optional<BernsteinVolume> volume_;
  Eigen::Affine3d toParameter_;
  double lipschitz_ = 1.0;
};

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

/// Multiplicities to give the interior knots for a C0 join of Bezier pieces of `degree`.
void pieceMultiplicities(TColStd_Array1OfInteger& mults, int degree) {
  for (Standard_Integer i = mults.Lower(); i <= mults.Upper(); ++i)
    mults(i) = (i == mults.Lower() || i == mults.Upper()) ? degree + 1 : degree;
}

void checkClamped(const TColStd_Array1OfInteger& mults, int degree, const std::string& where) {
  if (mults(mults.Lower()) != degree + 1 || mults(mults.Upper()) != degree + 1)
    throw CadError(where + ": an unclamped B-spline (end knot multiplicity below degree + 1) is not supported");
}

/// The deformation of one part's surfaces, curves and points (BRepTools_Modifier calls it for every
/// face, edge and vertex once; shared ones are shared in the result).
class FfdModification : public BRepTools_Modification {
 public:
  FfdModification(const FfdMap& map, const gp_Trsf& placement, const TopoDS_Shape& shape, const std::string& part)
      : map_(map), placement_(placement), part_(part) {
    TopExp::MapShapes(shape, TopAbs_FACE, faces_);
    TopExp::MapShapes(shape, TopAbs_EDGE, edges_);
  }

  int maxDegree() const { return maxDegree_; }

  Standard_Boolean NewSurface(const TopoDS_Face& face, Handle(Geom_Surface)& surface, TopLoc_Location& location,
                              Standard_Real& tolerance, Standard_Boolean& revWires, Standard_Boolean& revFace) override {
    surface = BRep_Tool::Surface(face, location);
    if (surface.IsNull()) return Standard_False;
    const std::string where = "part '" + part_ + "', face " + std::to_string(faces_.FindIndex(face));
    if (map_.options().method == CadMethod::Exact) requireInside(face, where);
    Handle(Geom_BSplineSurface) bs = asBSpline(surface, where);
    bs->Transform(placement_ * location.Transformation());
    Handle(Geom_BSplineSurface) moved =
        map_.options().method == CadMethod::Exact ? composeSurface(bs, where) : movePoles(bs);
    if (!location.IsIdentity()) moved->Transform(location.Transformation().Inverted());
    surface = moved;
    tolerance = BRep_Tool::Tolerance(face) * std::max(1.0, map_.lipschitz());
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
    if (map_.options().method == CadMethod::Exact) requireInside(edge, where);
    Handle(Geom_BSplineCurve) bs = asBSpline(curve, first, last, where);
    bs->Transform(placement_ * location.Transformation());
    Handle(Geom_BSplineCurve) moved = map_.options().method == CadMethod::Exact ? composeCurve(bs, where) : movePoles(bs);
    if (!location.IsIdentity()) moved->Transform(location.Transformation().Inverted());
    curve = moved;
    tolerance = BRep_Tool::Tolerance(edge) * std::max(1.0, map_.lipschitz());
    return Standard_True;
  }

  Standard_Boolean NewPoint(const TopoDS_Vertex& vertex, gp_Pnt& point, Standard_Real& tolerance) override {
    const gp_Pnt world = BRep_Tool::Pnt(vertex).Transformed(placement_);
    if (map_.options().method == CadMethod::Exact) requireInside(toEigen(world), "part '" + part_ + "', a vertex");
    point = toPnt(map_.point(toEigen(world)));
    tolerance = BRep_Tool::Tolerance(vertex) * std::max(1.0, map_.lipschitz());
    return Standard_True;
  }

  Standard_Boolean NewCurve2d(const TopoDS_Edge& edge, const TopoDS_Face& face, const TopoDS_Edge&, const TopoDS_Face&,
                              Handle(Geom2d_Curve)& curve, Standard_Real& tolerance) override {
    // The surfaces keep their parameters (same knots), so every p-curve stays as it is.
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
  void requireInside(const Eigen::Vector3d& world, const std::string& where) const {
    if (map_.extrapolates() || map_.inside(world)) return;
    const Eigen::Vector3d uvw = map_.parameters(world);
    throw CadError(where + " lies outside the lattice (lattice parameters (" + std::to_string(uvw.x()) + ", " +
                   std::to_string(uvw.y()) + ", " + std::to_string(uvw.z()) +
                   ")): with the Identity outside policy the FFD is not one polynomial there; enlarge the lattice "
                   "or use the Extrapolate policy (approximating the Identity case is not implemented)");
  }

  /// The trimmed face inside the lattice, checked on a 17 x 17 grid of its parameters classified
  /// against its boundary (its surface may extend beyond it: that part is trimmed away).
  void requireInside(const TopoDS_Face& face, const std::string& where) const {
    if (map_.extrapolates()) return;
    Standard_Real u0, u1, v0, v1;
    BRepTools::UVBounds(face, u0, u1, v0, v1);
    BRepAdaptor_Surface surface(face, false);
    BRepTopAdaptor_FClass2d classifier(face, Precision::PConfusion());
    const int n = 16;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) {
        const gp_Pnt2d uv(u0 + (u1 - u0) * i / n, v0 + (v1 - v0) * j / n);
        if (classifier.Perform(uv) == TopAbs_OUT) continue;
        requireInside(toEigen(surface.Value(uv.X(), uv.Y()).Transformed(placement_)), where);
      }
  }

  /// The edge inside the lattice, checked at 33 points of its range.
  void requireInside(const TopoDS_Edge& edge, const std::string& where) const {
    if (map_.extrapolates()) return;
    BRepAdaptor_Curve curve(edge);
    const int n = 32;
    for (int i = 0; i <= n; ++i) {
      const double t = curve.FirstParameter() + (curve.LastParameter() - curve.FirstParameter()) * i / n;
      requireInside(toEigen(curve.Value(t).Transformed(placement_)), where);
    }
  }

  void noteDegree(int degree, const std::string& where) {
    const int limit = map_.options().maxDegree;
    if (degree > limit)
      throw CadError(where + ": the exact composition has degree " + std::to_string(degree) + ", above the limit of " +
                     std::to_string(limit) + " (CadDeformOptions::maxDegree; a lattice of fewer control points lowers "
                     "it; approximation above the limit is not implemented)");
    maxDegree_ = std::max(maxDegree_, degree);
  }

  Handle(Geom_BSplineSurface) composeSurface(const Handle(Geom_BSplineSurface)& bs, const std::string& where) {
    const int p = bs->UDegree();
    const int q = bs->VDegree();
    const int d = map_.volume().totalDegree();
    noteDegree(std::max(d * p, d * q), where);
    TColStd_Array1OfInteger originalUMults(1, bs->NbUKnots()), originalVMults(1, bs->NbVKnots());
    bs->UMultiplicities(originalUMults);
    bs->VMultiplicities(originalVMults);
    checkClamped(originalUMults, p, where);
    checkClamped(originalVMults, q, where);
    // Bezier extraction by knot insertion: the pieces share their boundary poles and weights exactly.
    for (Standard_Integer i = 2; i < bs->NbUKnots(); ++i) bs->IncreaseUMultiplicity(i, p);
    for (Standard_Integer i = 2; i < bs->NbVKnots(); ++i) bs->IncreaseVMultiplicity(i, q);
    const int nu = bs->NbUKnots() - 1;
    const int nv = bs->NbVKnots() - 1;
    const bool rational = bs->IsURational() || bs->IsVRational();
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
        for (int b = 0; b <= q; ++b)
          for (int a = 0; a <= p; ++a) {
            const Eigen::Index row = a + (p + 1) * b;
            piece.poles.row(row) = toEigen(bs->Pole(su * p + a + 1, sv * q + b + 1)).transpose();
            if (rational) piece.weights[row] = bs->Weight(su * p + a + 1, sv * q + b + 1);
          }
        const BezierPatch composed = composeBezierPatch(map_.volume(), piece);
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
    pieceMultiplicities(um, du);
    pieceMultiplicities(vm, dv);
    Handle(Geom_BSplineSurface) out = rational ? new Geom_BSplineSurface(poles, weights, uk, vk, um, vm, du, dv)
                                               : new Geom_BSplineSurface(poles, uk, vk, um, vm, du, dv);
    // The composition of a C^k join is C^k: remove the knots the C0 join of the pieces added, where
    // OpenCASCADE finds them removable within rounding (a join stays C0 otherwise).
    const double tolerance = removalTolerance(poles);
    for (Standard_Integer i = 2; i <= nu; ++i)
      out->RemoveUKnot(i, std::max(0, du - (p - originalUMults(i))), tolerance);
    for (Standard_Integer i = 2; i <= nv; ++i)
      out->RemoveVKnot(i, std::max(0, dv - (q - originalVMults(i))), tolerance);
    return out;
  }

  Handle(Geom_BSplineCurve) composeCurve(const Handle(Geom_BSplineCurve)& bs, const std::string& where) {
    const int p = bs->Degree();
    const int d = map_.volume().totalDegree();
    noteDegree(d * p, where);
    TColStd_Array1OfInteger originalMults(1, bs->NbKnots());
    bs->Multiplicities(originalMults);
    checkClamped(originalMults, p, where);
    for (Standard_Integer i = 2; i < bs->NbKnots(); ++i) bs->IncreaseMultiplicity(i, p);
    const int n = bs->NbKnots() - 1;
    const bool rational = bs->IsRational();
    const int dp = d * p;
    TColgp_Array1OfPnt poles(1, n * dp + 1);
    TColStd_Array1OfReal weights(1, n * dp + 1);
    BezierPatch piece;
    piece.degreeU = p;
    piece.degreeV = 0;
    piece.poles.resize(p + 1, 3);
    if (rational) piece.weights.resize(p + 1);
    for (int s = 0; s < n; ++s) {
      for (int a = 0; a <= p; ++a) {
        piece.poles.row(a) = toEigen(bs->Pole(s * p + a + 1)).transpose();
        if (rational) piece.weights[a] = bs->Weight(s * p + a + 1);
      }
      const BezierPatch composed = composeBezierPatch(map_.volume(), piece);
      for (int a = 0; a <= dp; ++a) {
        poles(s * dp + a + 1) = toPnt(composed.poles.row(a).transpose());
        weights(s * dp + a + 1) = rational ? composed.weights[a] : 1.0;
      }
    }
    TColStd_Array1OfReal knots(1, n + 1);
    bs->Knots(knots);
    TColStd_Array1OfInteger mults(1, n + 1);
    pieceMultiplicities(mults, dp);
    Handle(Geom_BSplineCurve) out = rational ? new Geom_BSplineCurve(poles, weights, knots, mults, dp)
                                             : new Geom_BSplineCurve(poles, knots, mults, dp);
    TColgp_Array2OfPnt asGrid(1, poles.Length(), 1, 1);
    for (Standard_Integer i = 1; i <= poles.Length(); ++i) asGrid(i, 1) = poles(i);
    const double tolerance = removalTolerance(asGrid);
    for (Standard_Integer i = 2; i <= n; ++i) out->RemoveKnot(i, std::max(0, dp - (p - originalMults(i))), tolerance);
    return out;
  }

  /// Knot removal may move the geometry by 1e-12 of the poles' extent (rounding, for a join that is
  /// as smooth as the original's).
  static double removalTolerance(const TColgp_Array2OfPnt& poles) {
    Eigen::AlignedBox3d box;
    for (Standard_Integer i = poles.LowerRow(); i <= poles.UpperRow(); ++i)
      for (Standard_Integer j = poles.LowerCol(); j <= poles.UpperCol(); ++j) box.extend(toEigen(poles(i, j)));
    return 1e-12 * std::max(box.diagonal().norm(), 1e-300);
  }

  Handle(Geom_BSplineSurface) movePoles(const Handle(Geom_BSplineSurface)& bs) {
    maxDegree_ = std::max({maxDegree_, bs->UDegree(), bs->VDegree()});
    for (Standard_Integer i = 1; i <= bs->NbUPoles(); ++i)
      for (Standard_Integer j = 1; j <= bs->NbVPoles(); ++j)
        bs->SetPole(i, j, toPnt(map_.point(toEigen(bs->Pole(i, j)))), bs->Weight(i, j));
    return bs;
  }

  Handle(Geom_BSplineCurve) movePoles(const Handle(Geom_BSplineCurve)& bs) {
    maxDegree_ = std::max(maxDegree_, bs->Degree());
    for (Standard_Integer i = 1; i <= bs->NbPoles(); ++i)
      bs->SetPole(i, toPnt(map_.point(toEigen(bs->Pole(i)))), bs->Weight(i));
    return bs;
  }

  const FfdMap& map_;
  gp_Trsf placement_;
  std::string part_;
  TopTools_IndexedMapOfShape faces_;
  TopTools_IndexedMapOfShape edges_;
  int maxDegree_ = 0;
};

/// True when a sub-shape below the root carries a placement of its own (the modifier's frames
/// would then differ between its passes).
bool hasInnerLocations(const TopoDS_Shape& shape) {
  for (TopoDS_Iterator it(shape, false, false); it.More(); it.Next())
    if (!it.Value().Location().IsIdentity() || hasInnerLocations(it.Value())) return true;
  return false;
}

/// Max |S'(s,t) - X(S(s,t))| over a grid per face (the points inside its trim), and max distance between each edge's 3D curve
/// and its curves on the faces that share it.
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
    for (int i = 0; i < samples; ++i)
      for (int j = 0; j < samples; ++j) {
        const double u = u0 + (u1 - u0) * i / std::max(1, samples - 1);
        const double v = v0 + (v1 - v0) * j / std::max(1, samples - 1);
        if (classifier.Perform(gp_Pnt2d(u, v)) == TopAbs_OUT) continue;  // trimmed away
        const Eigen::Vector3d expected = map.point(toEigen(before.Value(u, v).Transformed(placement)));
        report.maxDeviation = std::max(report.maxDeviation, (toEigen(after.Value(u, v)) - expected).norm());
      }
  }
  TopTools_IndexedDataMapOfShapeListOfShape facesOfEdge;
  TopExp::MapShapesAndAncestors(deformed, TopAbs_EDGE, TopAbs_FACE, facesOfEdge);
  for (Standard_Integer e = 1; e <= facesOfEdge.Extent(); ++e) {
    const TopoDS_Edge& edge = TopoDS::Edge(facesOfEdge.FindKey(e));
    if (BRep_Tool::Degenerated(edge) || !BRep_Tool::IsGeometric(edge)) continue;
    BRepAdaptor_Curve curve(edge);
    for (TopTools_ListIteratorOfListOfShape f(facesOfEdge(e)); f.More(); f.Next()) {
      BRepAdaptor_Curve onFace(edge, TopoDS::Face(f.Value()));
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
  const FfdMap map(lattice, options);
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
      Handle(FfdModification) modification = new FfdModification(map, placement, nurbs, part.name);
      BRepTools_Modifier modifier(nurbs);
      modifier.Perform(modification);
      if (!modifier.IsDone()) throw CadError(context + ": OpenCASCADE's modifier did not complete");
      const TopoDS_Shape deformed = modifier.ModifiedShape(nurbs);
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      result.model.data().parts.push_back({part.name, deformed});
      TopTools_IndexedMapOfShape faces, edges;
      TopExp::MapShapes(nurbs, TopAbs_FACE, faces);
      TopExp::MapShapes(nurbs, TopAbs_EDGE, edges);
      result.report.faces += faces.Extent();
      result.report.edges += edges.Extent();
      result.report.maxDegree = std::max(result.report.maxDegree, modification->maxDegree());
      if (options.samples > 0) measure(nurbs, placement, deformed, modifier, map, options.samples, result.report);
    });
  }
  result.report.seconds = seconds;
  return result;
}

}  // namespace ffdkit::cad
