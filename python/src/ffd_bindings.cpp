// ffdkit.ffd: lattices, embedding and deformation (pipelines and direct manipulation:
// ffd_pipeline_bindings.cpp).
// Names mirror the C++ API (ffd/include/ffdkit/ffd/*.h); see docs/python.md.

#include <memory>
#include <string>
#include <utility>

#include <pybind11/eigen.h>
#include <pybind11/operators.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "ffd_binding_support.h"
#include "ffdkit/ffd/bernstein_basis.h"
#include "ffdkit/ffd/bspline_basis.h"
#include "ffdkit/ffd/cylindrical_lattice.h"
#include "ffdkit/ffd/deformer.h"
#include "ffdkit/ffd/direct_manipulation.h"
#include "ffdkit/ffd/embedding.h"
#include "ffdkit/ffd/lattice.h"
#include "ffdkit/ffd/pipeline.h"
#include "numpy_eigen.h"

namespace ffdkit::python {

using namespace pybind11::literals;

namespace {


std::array<ffd::AxisBasis, 3> basesArg(const py::object& bases, const ffd::AxisBasis& fallback) {
  if (bases.is_none()) return {fallback, fallback, fallback};
  if (py::isinstance<ffd::AxisBasis>(bases)) {
    const auto one = bases.cast<ffd::AxisBasis>();
    return {one, one, one};
  }
  const auto list = bases.cast<std::vector<ffd::AxisBasis>>();
  if (list.size() != 3) {
    throw py::value_error("bases: expected one AxisBasis or three (u, v, w), got " + std::to_string(list.size()));
  }
  return {list[0], list[1], list[2]};
}

std::string basisRepr(const ffd::AxisBasis& basis) {
  switch (basis.kind) {
    case ffd::AxisBasis::Kind::Bernstein: return "AxisBasis.bernstein()";
    case ffd::AxisBasis::Kind::PeriodicBSpline: return "AxisBasis.periodic(" + std::to_string(basis.degree) + ")";
    case ffd::AxisBasis::Kind::BSpline:
      return basis.knots.size() ? "AxisBasis.bsplineWithKnots(" + std::to_string(basis.degree) + ", <" +
                                      std::to_string(basis.knots.size()) + " knots>)"
                                : "AxisBasis.bspline(" + std::to_string(basis.degree) + ")";
  }
  return "AxisBasis()";
}

// The arguments (options, progress) of the embedding calls: EmbedOptions with the Python
// progress callback bridged into it.
struct EmbedArgs {
  EmbedArgs(const py::object& options, const py::object& callback) : progress(callback) {
    if (!options.is_none()) embed = options.cast<ffd::EmbedOptions>();
    embed.progress = progress.embedHook();
  }
  PythonProgress progress;
  ffd::EmbedOptions embed;
};


void bindLattice(py::module_& m) {
  py::class_<ffd::AxisBasis> basis(m, "AxisBasis", R"doc(The basis of one lattice axis: Bernstein, clamped B-spline or periodic B-spline.

Make one with AxisBasis.bernstein(), .bspline(degree), .bsplineWithKnots(degree, knots) or
.periodic(degree); a Lattice resolves it for its number of control points (ffd/axis_basis.h).
Fields: kind (AxisBasis.Kind), degree, knots.)doc");
  py::enum_<ffd::AxisBasis::Kind>(basis, "Kind", R"doc(The kind of an axis basis.

Bernstein (degree count-1, domain [0, 1]), BSpline (clamped, uniform knots unless given) or
PeriodicBSpline (a closed axis, e.g. the angle of a cylindrical lattice).)doc")
      .value("Bernstein", ffd::AxisBasis::Kind::Bernstein)
      .value("BSpline", ffd::AxisBasis::Kind::BSpline)
      .value("PeriodicBSpline", ffd::AxisBasis::Kind::PeriodicBSpline);
  basis.def(py::init<>(), R"doc(A clamped cubic B-spline basis (the default).

Use the static constructors (bernstein(), bspline(), ...) for the others.)doc")
      .def_readwrite("kind", &ffd::AxisBasis::kind)
      .def_readwrite("degree", &ffd::AxisBasis::degree)
      .def_readwrite("knots", &ffd::AxisBasis::knots)
      .def_static("bernstein", &ffd::AxisBasis::bernstein, R"doc(The Bernstein (Bezier) basis: degree count-1 on [0, 1] (Sederberg & Parry 1986).

Returns:
    AxisBasis. Valid for any number of control points >= 2.)doc")
      .def_static("bspline", &ffd::AxisBasis::bspline, "degree"_a = 3, R"doc(A clamped uniform B-spline basis.

Args:
    degree: polynomial degree, 1 <= degree <= count-1 of the lattice axis (checked by the lattice).
Returns:
    AxisBasis.)doc")
      .def_static("bsplineWithKnots", &ffd::AxisBasis::bsplineWithKnots, "degree"_a, "knots"_a, R"doc(A B-spline basis with explicit knots.

Args:
    degree: polynomial degree.
    knots: non-decreasing knots, count + degree + 1 of them for an axis of `count` points.
Returns:
    AxisBasis. A lattice built with it raises LatticeError for a bad knot vector.)doc")
      .def_static("periodic", &ffd::AxisBasis::periodic, "degree"_a = 3, R"doc(A periodic (closed) uniform B-spline basis, for an angular axis.

Args:
    degree: polynomial degree (default 3).
Returns:
    AxisBasis with domain [0, 1) that wraps.)doc")
      .def("__repr__", &basisRepr);

  py::class_<ffd::OutsidePolicy> policy(m, "OutsidePolicy", R"doc(What happens to object points outside the rest lattice (ffd/outside_policy.h).

Make one with OutsidePolicy.identity() (the default: left where they are), .clampEdge(),
.extrapolate() or .falloff(distance). Fields: kind (OutsidePolicy.Kind), distance.)doc");
  py::enum_<ffd::OutsidePolicy::Kind>(policy, "Kind", R"doc(The kind of outside behaviour.

Identity (left unchanged), ClampEdge (follow the nearest boundary point), Extrapolate
(evaluate the end polynomial pieces) or Falloff (ClampEdge blended to Identity over a distance).)doc")
      .value("Identity", ffd::OutsidePolicy::Kind::Identity)
      .value("ClampEdge", ffd::OutsidePolicy::Kind::ClampEdge)
      .value("Extrapolate", ffd::OutsidePolicy::Kind::Extrapolate)
      .value("Falloff", ffd::OutsidePolicy::Kind::Falloff);
  policy.def(py::init<>(), R"doc(The Identity policy: outside points are left where they are.

Use the static constructors for the others.)doc")
      .def_readwrite("kind", &ffd::OutsidePolicy::kind)
      .def_readwrite("distance", &ffd::OutsidePolicy::distance)
      .def_static("identity", &ffd::OutsidePolicy::identity, R"doc(Outside points are left where they are (the default).

Returns:
    OutsidePolicy.)doc")
      .def_static("clampEdge", &ffd::OutsidePolicy::clampEdge, R"doc(Outside points keep their offset from the nearest boundary point of the rest lattice.

Returns:
    OutsidePolicy (Blender's lattice behaviour).)doc")
      .def_static("extrapolate", &ffd::OutsidePolicy::extrapolate, R"doc(Outside points follow the end polynomial pieces beyond the box (meant for Bernstein bases).

Returns:
    OutsidePolicy.)doc")
      .def_static("falloff", &ffd::OutsidePolicy::falloff, "distance"_a, R"doc(ClampEdge at the lattice boundary, blended to Identity at `distance` from it.

Args:
    distance: blend length in lattice-local units, > 0 (a lattice raises LatticeError otherwise).
Returns:
    OutsidePolicy.)doc")
      .def(py::self == py::self)
      .def("__repr__", [](const ffd::OutsidePolicy& p) {
        return "OutsidePolicy(" + std::string(py::str(py::cast(p.kind))) + ", distance=" + std::to_string(p.distance) + ")";
      });

  py::class_<ffd::Lattice>(m, "Lattice", R"doc(An FFD lattice of l x m x n control points (ffd/lattice.h).

Control points are lattice-local, one per row, flat index i + l*(j + m*k); world = frame @ local.
Lattice(counts, bases, restPoints, frame=None) builds a user-shaped lattice; makeBoxLattice and
makeCylindricalLattice build the common shapes. controlPoints is a writable numpy view.
Raises LatticeError (a ValueError) for bad counts, bases, shapes or non-finite values.)doc")
      .def(py::init([](const Eigen::Vector3i& counts, const py::object& bases, const py::object& restPoints,
                       const py::object& frame) {
             const PointsArg rest(restPoints, "restPoints");
             return ffd::Lattice(counts, basesArg(bases, ffd::AxisBasis::bernstein()), rest.ref(),
                                 affineArg(frame, "frame"));
           }),
           "counts"_a, "bases"_a, "restPoints"_a, "frame"_a = py::none(), R"doc(A lattice with the given rest points.

Args:
    counts: (l, m, n) control points per axis, each >= 2.
    bases: one AxisBasis for all axes or three (u, v, w).
    restPoints: l*m*n x 3 lattice-local rest points, flat index i + l*(j + m*k).
    frame: 4 x 4 world placement (default identity).
Raises:
    LatticeError: counts < 2, a degree the count cannot carry, bad knots, a wrong row count or
        non-finite values. ValueError: restPoints of the wrong shape.)doc")
      .def_property_readonly("counts", &ffd::Lattice::counts)
      .def_property_readonly("pointCount", &ffd::Lattice::pointCount)
      .def("index", [](const ffd::Lattice& l, int i, int j, int k) {
        const Eigen::Vector3i c = l.counts();
        if (i < 0 || j < 0 || k < 0 || i >= c[0] || j >= c[1] || k >= c[2]) {
          throw py::index_error("index (" + std::to_string(i) + ", " + std::to_string(j) + ", " + std::to_string(k) +
                                ") is outside the lattice grid");
        }
        return l.index(i, j, k);
      }, "i"_a, "j"_a, "k"_a, R"doc(The flat index i + l*(j + m*k) of grid point (i, j, k).

Args:
    i, j, k: grid indices along u, v, w.
Raises:
    IndexError: (i, j, k) is outside the grid.)doc")
      .def("gridIndex", &ffd::Lattice::gridIndex, "flat"_a, R"doc(The grid index (i, j, k) of flat index `flat`.

Args:
    flat: 0 <= flat < pointCount.
Raises:
    LatticeError: flat is out of range.)doc")
      .def("basis", [](const ffd::Lattice& l, int axis) { return l.basis(axis); }, "axis"_a, R"doc(The basis of an axis, as given.

Args:
    axis: 0 (u), 1 (v) or 2 (w).
Returns:
    AxisBasis.)doc")
      .def("knots", [](const ffd::Lattice& l, int axis) { return l.axis(axis).knots(); }, "axis"_a, R"doc(The resolved knot vector of an axis.

Args:
    axis: 0 (u), 1 (v) or 2 (w).
Returns:
    list of floats (Bernstein: count zeros followed by count ones).)doc")
      .def("greville", [](const ffd::Lattice& l, int axis) { return l.axis(axis).greville(); }, "axis"_a, R"doc(The Greville abscissae of an axis: the parameter each control point sits over.

Args:
    axis: 0 (u), 1 (v) or 2 (w).
Returns:
    list of floats, one per control point along the axis.)doc")
      .def("degree", [](const ffd::Lattice& l, int axis) { return l.axis(axis).degree(); }, "axis"_a, R"doc(The polynomial degree of an axis.

Args:
    axis: 0 (u), 1 (v) or 2 (w).
Returns:
    int (count-1 for Bernstein).)doc")
      .def_property_readonly("parameterMin", &ffd::Lattice::parameterMin)
      .def_property_readonly("parameterMax", &ffd::Lattice::parameterMax)
      .def_property(
          "controlPoints",
          [](py::object self) {
            auto& lattice = self.cast<ffd::Lattice&>();
            return viewOf(lattice.controlPoints(), self, /*writeable=*/true);
          },
          [](ffd::Lattice& l, const py::object& points) { l.setControlPoints(PointsArg(points, "controlPoints").ref()); },
          "Current control points, pointCount x 3 (a writable view: edits act on the lattice).")
      .def_property_readonly("restPoints",
                             [](py::object self) { return viewOf(self.cast<ffd::Lattice&>().restPoints(), self, false); })
      .def("setControlPoints",
           [](ffd::Lattice& l, const py::object& points) { l.setControlPoints(PointsArg(points, "points").ref()); },
           "points"_a, R"doc(Sets every control point.

Args:
    points: pointCount x 3, lattice-local.
Raises:
    LatticeError: wrong row count or non-finite values. ValueError: not N x 3.)doc")
      .def("setControlPoint", &ffd::Lattice::setControlPoint, "flat"_a, "point"_a, R"doc(Sets one control point.

Args:
    flat: its flat index.
    point: its new lattice-local position (3 numbers).
Raises:
    LatticeError: flat out of range or a non-finite point.)doc")
      .def("resetToRest", &ffd::Lattice::resetToRest, R"doc(Moves every control point back to its rest position.

Bumps the revision; the rest lattice and the frame are unchanged.)doc")
      .def("setRestPoints",
           [](ffd::Lattice& l, const py::object& points) { l.setRestPoints(PointsArg(points, "restPoints").ref()); },
           "restPoints"_a, R"doc(Replaces the rest lattice and resets the control points to it.

Args:
    restPoints: pointCount x 3, lattice-local.
Raises:
    LatticeError: wrong row count or non-finite values. Embeddings built before are stale.)doc")
      .def_property("frame", [](const ffd::Lattice& l) { return affineToArray(l.frame()); },
                    [](ffd::Lattice& l, const py::object& f) { l.setFrame(affineArg(f, "frame")); })
      .def("setFrame", [](ffd::Lattice& l, const py::object& f) { l.setFrame(affineArg(f, "frame")); }, "frame"_a, R"doc(Moves the whole lattice in the world; local coordinates are unchanged.

Args:
    frame: 4 x 4 affine placement, world = frame @ local.
Raises:
    LatticeError: a non-finite or singular frame. Embeddings built before are stale.)doc")
      .def_property("outsidePolicy", &ffd::Lattice::outsidePolicy, &ffd::Lattice::setOutsidePolicy)
      .def("setOutsidePolicy", &ffd::Lattice::setOutsidePolicy, "policy"_a, R"doc(Sets what happens to points outside the rest lattice.

Args:
    policy: an OutsidePolicy.
Raises:
    LatticeError: Falloff with a distance <= 0. Embeddings built before are stale.)doc")
      .def_property_readonly("revision", &ffd::Lattice::revision)
      .def_property_readonly("restRevision", &ffd::Lattice::restRevision)
      .def("evaluate",
           [](ffd::Lattice& l, const py::object& uvw) {
             const PointsArg parameters(uvw, "uvw");
             synced(l);
             Eigen::MatrixX3d out(parameters.rows(), 3);
             for (Eigen::Index r = 0; r < out.rows(); ++r) {
               out.row(r) = l.evaluate(parameters.ref().row(r).transpose()).transpose();
             }
             return toArray(std::move(out));
           },
           "uvw"_a, R"doc(X(u,v,w) for each row of uvw (Kuriyama 1996, eq. (6.1)), lattice-local.

Args:
    uvw: N x 3 parameters.
Returns:
    N x 3 points. Parameters outside the box evaluate the end polynomial pieces.
Raises:
    ValueError: uvw is not N x 3.)doc")
      .def("evaluateRest",
           [](const ffd::Lattice& l, const py::object& uvw) {
             const PointsArg parameters(uvw, "uvw");
             Eigen::MatrixX3d out(parameters.rows(), 3);
             for (Eigen::Index r = 0; r < out.rows(); ++r) {
               out.row(r) = l.evaluateRest(parameters.ref().row(r).transpose()).transpose();
             }
             return toArray(std::move(out));
           },
           "uvw"_a, R"doc(Xbar(u,v,w): eq. (6.1) on the rest lattice, for each row of uvw.

Args:
    uvw: N x 3 parameters.
Returns:
    N x 3 lattice-local points.)doc")
      .def("jacobian", [](ffd::Lattice& l, const Eigen::Vector3d& uvw) { return synced(l).jacobian(uvw); }, "uvw"_a, R"doc(The 3 x 3 derivative dX/d(u,v,w) at one parameter (column a: along parameter a).

Args:
    uvw: three parameters.
Returns:
    3 x 3 array, lattice-local.)doc")
      .def_property_readonly("restIsAffine", &ffd::Lattice::restIsAffine)
      .def_property_readonly("restSize", &ffd::Lattice::restSize)
      .def("copy", [](const ffd::Lattice& l) { return ffd::Lattice(l); }, R"doc(An independent copy of the lattice.

Returns:
    Lattice (control points, rest points, frame, policy and revisions copied).)doc")
      .def("__repr__", [](const ffd::Lattice& l) {
        const Eigen::Vector3i c = l.counts();
        return "<ffdkit.ffd.Lattice " + std::to_string(c[0]) + "x" + std::to_string(c[1]) + "x" +
               std::to_string(c[2]) + ", " + basisRepr(l.basis(0)) + ", " + basisRepr(l.basis(1)) + ", " +
               basisRepr(l.basis(2)) + ">";
      });

  m.def("makeBoxLattice",
        [](const Eigen::Vector3i& counts, const py::object& bases, const Eigen::Vector3d& boxMin,
           const Eigen::Vector3d& boxMax, const py::object& frame, const ffd::OutsidePolicy& outsidePolicy,
           bool capDegreeToCount) {
          ffd::BoxLatticeOptions options;
          options.counts = counts;
          options.bases = basesArg(bases, ffd::AxisBasis::bspline(3));
          options.boxMin = boxMin;
          options.boxMax = boxMax;
          options.frame = affineArg(frame, "frame");
          options.outsidePolicy = outsidePolicy;
          options.capDegreeToCount = capDegreeToCount;
          return ffd::makeBoxLattice(options);
        },
        "counts"_a = Eigen::Vector3i(4, 4, 4), "bases"_a = py::none(), "boxMin"_a = Eigen::Vector3d::Zero().eval(),
        "boxMax"_a = Eigen::Vector3d::Ones().eval(), "frame"_a = py::none(),
        "outsidePolicy"_a = ffd::OutsidePolicy{}, "capDegreeToCount"_a = true, R"doc(A box lattice: control points on a regular grid of a box (ffd/box_lattice.h).

Args:
    counts: (l, m, n) control points per axis (default 4, 4, 4).
    bases: one AxisBasis or three (default: cubic B-splines).
    boxMin, boxMax: the box's corners, lattice-local (default the unit box).
    frame: 4 x 4 world placement (default identity).
    outsidePolicy: what happens to points outside (default Identity).
    capDegreeToCount: lower a B-spline degree an axis of few points cannot carry.
Raises:
    LatticeError: counts < 2, an empty box, bad bases or frame.)doc");
  m.def("makeLattice",
        [](const Eigen::Vector3i& counts, const py::object& bases, const py::object& restPoints, const py::object& frame) {
          return ffd::makeLattice(counts, basesArg(bases, ffd::AxisBasis::bernstein()),
                                  PointsArg(restPoints, "restPoints").ref(), affineArg(frame, "frame"));
        },
        "counts"_a, "bases"_a, "restPoints"_a, "frame"_a = py::none(), R"doc(A user-shaped lattice from its rest points.

Args:
    counts: (l, m, n) control points per axis.
    bases: one AxisBasis or three.
    restPoints: l*m*n x 3 lattice-local rest points.
    frame: 4 x 4 world placement (default identity).
Raises:
    LatticeError: bad counts, bases, row count or non-finite values.)doc");
  m.def("makeCylindricalLattice",
        [](const Eigen::Vector3i& counts, const py::object& bases, double innerRadius, double outerRadius, double zMin,
           double zMax, const py::object& frame, const ffd::OutsidePolicy& outsidePolicy) {
          ffd::CylindricalLatticeOptions options;
          options.counts = counts;
          if (!bases.is_none()) options.bases = basesArg(bases, ffd::AxisBasis::bspline(3));
          options.innerRadius = innerRadius;
          options.outerRadius = outerRadius;
          options.zMin = zMin;
          options.zMax = zMax;
          options.frame = affineArg(frame, "frame");
          options.outsidePolicy = outsidePolicy;
          return ffd::makeCylindricalLattice(options);
        },
        "counts"_a = Eigen::Vector3i(3, 8, 4), "bases"_a = py::none(), "innerRadius"_a = 0.0, "outerRadius"_a = 1.0,
        "zMin"_a = 0.0, "zMax"_a = 1.0, "frame"_a = py::none(), "outsidePolicy"_a = ffd::OutsidePolicy{}, R"doc(An EFFD cylindrical lattice (Coquillart 1990; Kuriyama 1996, Fig. 6-11).

Args:
    counts: (radial, angular, height) control points (default 3, 8, 4).
    bases: three AxisBasis; the angular one must be periodic (default cubic, periodic, cubic).
    innerRadius, outerRadius: radius range, 0 <= inner < outer.
    zMin, zMax: height range, zMin < zMax.
    frame, outsidePolicy: as for makeBoxLattice.
Raises:
    LatticeError: bad counts, radii, heights or bases.)doc");

  m.def("bernsteinBasis", &ffd::bernsteinBasis, "degree"_a, "t"_a, R"doc(The Bernstein polynomials of a degree at t.

Args:
    degree: n >= 0.
    t: parameter in [0, 1].
Returns:
    list of n + 1 values B_i^n(t).)doc");
  m.def("clampedUniformKnots", &ffd::clampedUniformKnots, "count"_a, "degree"_a, R"doc(The clamped uniform knot vector on [0, 1].

Args:
    count: control points, > degree.
    degree: polynomial degree >= 1.
Returns:
    list of count + degree + 1 knots.
Raises:
    LatticeError: unless 1 <= degree <= count - 1.)doc");
  m.def("periodicUniformKnots", &ffd::periodicUniformKnots, "count"_a, "degree"_a, R"doc(The uniform knot vector of a periodic B-spline axis.

Args:
    count: distinct control points around the axis.
    degree: polynomial degree.
Returns:
    list of count + 2 degree + 1 knots t_i = (i - degree) / count.
Raises:
    LatticeError: unless 1 <= degree <= count - 1.)doc");
  m.def("grevilleAbscissae", &ffd::grevilleAbscissae, "knots"_a, "count"_a, "degree"_a, R"doc(The Greville abscissae of a knot vector: the parameter each control point sits over.

Args:
    knots: the knot vector.
    count: control points.
    degree: polynomial degree.
Returns:
    list of count values.)doc");
}

void bindDeformation(py::module_& m) {
  py::enum_<ffd::PointStatus>(m, "PointStatus", R"doc(Where a point landed when it was embedded.

Inside (in the rest lattice), Outside (handled by the outside policy) or Failed (Newton did not
converge; the point is left unchanged). Embedding.statuses() holds int(PointStatus.X) per point.)doc")
      .value("Inside", ffd::PointStatus::Inside)
      .value("Outside", ffd::PointStatus::Outside)
      .value("Failed", ffd::PointStatus::Failed);

  py::class_<ffd::EmbedOptions>(m, "EmbedOptions", R"doc(Options of embed(): Newton tolerance and iterations, the boundary epsilon, threading.

EmbedOptions(tolerance=1e-13, maxIterations=40, boundaryEpsilon=1e-9, parallel=True). The
progress callback is the `progress` argument of embed() and Pipeline.update().)doc")
      .def(py::init([](double tolerance, int maxIterations, double boundaryEpsilon, bool parallel) {
             ffd::EmbedOptions options;
             options.tolerance = tolerance;
             options.maxIterations = maxIterations;
             options.boundaryEpsilon = boundaryEpsilon;
             options.parallel = parallel;
             return options;
           }),
           "tolerance"_a = 1e-13, "maxIterations"_a = 40, "boundaryEpsilon"_a = 1e-9, "parallel"_a = true, R"doc(Embedding options.

Args:
    tolerance: Newton stops when the residual is below tolerance x the lattice size.
    maxIterations: Newton iterations per point before it counts as Failed.
    boundaryEpsilon: parameters within this of the box count as inside.
    parallel: run on all OpenMP threads.)doc")
      .def_readwrite("tolerance", &ffd::EmbedOptions::tolerance)
      .def_readwrite("maxIterations", &ffd::EmbedOptions::maxIterations)
      .def_readwrite("boundaryEpsilon", &ffd::EmbedOptions::boundaryEpsilon)
      .def_readwrite("parallel", &ffd::EmbedOptions::parallel);
  m.attr("kEmbedProgressChunk") = ffd::kEmbedProgressChunk;

  py::class_<ffd::Embedding>(m, "Embedding", R"doc(The (u,v,w) of a point set in one rest lattice (ffd/embedding.h).

Made by embed(); a Deformer evaluates it. It remembers the lattice state it was built for
(restRevision): using it with a changed rest lattice raises LatticeError.)doc")
      .def_property_readonly("pointCount", &ffd::Embedding::pointCount)
      .def("status", &ffd::Embedding::status, "point"_a, R"doc(The status of one point.

Args:
    point: its index, original order.
Returns:
    PointStatus.
Raises:
    LatticeError: point out of range.)doc")
      .def("statuses",
           [](py::object self) {
             const auto& statuses = self.cast<const ffd::Embedding&>().statuses();
             py::array view(py::dtype::of<std::uint8_t>(), {static_cast<py::ssize_t>(statuses.size())},
                            {py::ssize_t(1)}, reinterpret_cast<const std::uint8_t*>(statuses.data()), self);
             py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
             return view;
           }, R"doc(The status of every point, as uint8 codes (0 Inside, 1 Outside, 2 Failed).

Returns:
    A read-only numpy view (N,) owned by the embedding; int(PointStatus.X) gives the codes.)doc")
      .def_property_readonly("insideCount", &ffd::Embedding::insideCount)
      .def_property_readonly("outsideCount", &ffd::Embedding::outsideCount)
      .def_property_readonly("failedCount", &ffd::Embedding::failedCount)
      .def("parameters", [](const ffd::Embedding& e) { return toArray(e.parameters()); }, R"doc(The parameters each point is evaluated at, N x 3, original order.

Returns:
    A new array: the Newton solution for inside points, the clamped one for ClampEdge/Falloff,
    the last iterate clamped into the box for Failed points; periodic parameters in [0, 1).)doc")
      .def_property_readonly("restRevision", &ffd::Embedding::restRevision)
      .def_property_readonly("latticeCounts", &ffd::Embedding::latticeCounts)
      .def_property_readonly("outsidePolicy", &ffd::Embedding::outsidePolicy)
      .def("checkLattice", &ffd::Embedding::checkLattice, "lattice"_a, R"doc(Checks that the embedding was built for this lattice.

Args:
    lattice: the lattice to use it with.
Raises:
    LatticeError: other counts or another rest revision ("embedding is stale ... re-embed").)doc")
      .def("memoryBytes", &ffd::Embedding::memoryBytes, R"doc(The heap bytes the embedding holds.

Returns:
    int (about 29 bytes per point for a box lattice).)doc");

  m.def("embed",
        [](const ffd::Lattice& lattice, const py::object& points, const py::object& options, const py::object& progress) {
          const PointsArg q(points, "points");
          const EmbedArgs args(options, progress);
          return withoutGil(args.progress, [&] { return ffd::embed(lattice, q.ref(), args.embed); });
        },
        "lattice"_a, "points"_a, "options"_a = py::none(), "progress"_a = py::none(), R"doc(Embeds world points in the rest lattice: finds (u,v,w) with Xbar(u,v,w) = Q (Kuriyama 1996, eq. (6.2)).

Args:
    lattice: the lattice (its rest points and frame are used).
    points: N x 3 world points, finite.
    options: EmbedOptions (default: EmbedOptions()).
    progress: callable(done, total) called on this thread about every 65,536 points; returning
        False cancels, None or True goes on.
Returns:
    Embedding. The interpreter lock is released while it runs.
Raises:
    LatticeError: non-finite points. ValueError: points not N x 3.
    Cancelled: progress returned False (an exception it raises is re-raised instead).)doc");

  m.def("deformPoints",
        [](ffd::Lattice& lattice, const py::object& points, const py::object& options, const py::object& progress) {
          const PointsArg q(points, "points");
          const EmbedArgs args(options, progress);
          synced(lattice);
          auto deformer = std::make_unique<ffd::Deformer>();
          withoutGil(args.progress, [&] {
            *deformer = ffd::Deformer(ffd::embed(lattice, q.ref(), args.embed));
            return &deformer->deform(lattice, q.ref());
          });
          // The result is the private deformer's output buffer (no copy); the deformer, and with
          // it the embedding (about 29 bytes per point), lives as long as the array.
          const ffd::Deformer* owned = deformer.release();
          py::capsule owner(owned, [](void* p) { delete static_cast<const ffd::Deformer*>(p); });
          return viewOf(owned->points(), owner, true);
        },
        "lattice"_a, "points"_a, "options"_a = py::none(), "progress"_a = py::none(), R"doc(One-shot FFD of a point set: embed, then deform through the lattice's current control points.

Args:
    lattice: the lattice.
    points: N x 3 world points.
    options: EmbedOptions (default: EmbedOptions()).
    progress: callable(done, total), as for embed().
Returns:
    A new writable (N, 3) array of deformed world points (it also holds the embedding, about 29
    bytes per point). The interpreter lock is released while it runs.
Raises:
    LatticeError, ValueError, Cancelled: as embed().)doc");

  py::class_<ffd::DeformStats>(m, "DeformStats", R"doc(What the last Deformer.deform() or update() evaluated.

Fields: full (every point evaluated), changedControlPoints, evaluatedPoints.)doc")
      .def_readonly("full", &ffd::DeformStats::full)
      .def_readonly("changedControlPoints", &ffd::DeformStats::changedControlPoints)
      .def_readonly("evaluatedPoints", &ffd::DeformStats::evaluatedPoints);

  // Deformer results are read-only views of Deformer.points: the next deform()/update() rewrites them.
  using Evaluation = const Eigen::MatrixX3d& (ffd::Deformer::*)(const ffd::Lattice&, const Eigen::Ref<const Eigen::MatrixX3d>&);
  auto evaluate = [](py::object self, ffd::Lattice& lattice, const py::object& input, Evaluation evaluation) {
    auto& deformer = self.cast<ffd::Deformer&>();
    const PointsArg q(input, "input");
    synced(lattice);
    withoutGil(PythonProgress(py::none()), [&] { return &(deformer.*evaluation)(lattice, q.ref()); });
    return viewOf(deformer.points(), self, false);
  };
  py::enum_<ffd::Precision>(m, "Precision", R"doc(Arithmetic of the deformation: Double (the default) or Single.

Single computes float32 displacements, within 1e-6 of the largest control-point move
(ffd/deformer.h); Deformer.precision and Pipeline.precision select it.)doc")
      .value("Double", ffd::Precision::Double)
      .value("Single", ffd::Precision::Single);
  py::class_<ffd::Deformer>(m, "Deformer", R"doc(Maps embedded points through a lattice (ffd/deformer.h): embed once, deform per frame.

Deformer.fromPoints(lattice, points) embeds and keeps the embedding; deform() evaluates every
point, update() only the points whose cells hold a moved control point. Results are read-only
views of Deformer.points that the next call rewrites (.copy() to keep one).)doc")
      .def(py::init<>(), R"doc(An empty deformer (no embedding).

Use Deformer.fromPoints or Deformer(embedding).)doc")
      .def(py::init<ffd::Embedding>(), "embedding"_a, R"doc(A deformer for the points of an embedding.

Args:
    embedding: an Embedding; it is copied.)doc")
      .def_static("fromPoints",
                  [](const ffd::Lattice& lattice, const py::object& points, const py::object& options,
                     const py::object& progress) {
                    const PointsArg q(points, "points");
                    const EmbedArgs args(options, progress);
                    return withoutGil(args.progress,
                                      [&] { return ffd::Deformer(ffd::embed(lattice, q.ref(), args.embed)); });
                  },
                  "lattice"_a, "points"_a, "options"_a = py::none(), "progress"_a = py::none(), R"doc(Embeds the points and returns a deformer that keeps the embedding (no copy).

Args:
    lattice: the lattice (rest points and frame).
    points: N x 3 world points.
    options: EmbedOptions (default: EmbedOptions()).
    progress: callable(done, total), as for embed().
Returns:
    Deformer. The interpreter lock is released while it embeds.
Raises:
    LatticeError, ValueError, Cancelled: as embed().)doc")
      .def_property_readonly("embedding", &ffd::Deformer::embedding, py::return_value_policy::reference_internal)
      .def("deform", [evaluate](py::object self, ffd::Lattice& lattice, const py::object& input) {
        return evaluate(self, lattice, input, &ffd::Deformer::deform);
      }, "lattice"_a, "input"_a, R"doc(Evaluates every point through the lattice's current control points.

Args:
    lattice: the lattice the embedding was built for.
    input: the N x 3 world points that were embedded.
Returns:
    N x 3 deformed world points (a read-only view of Deformer.points).
Raises:
    LatticeError: the embedding is stale for the lattice, or input has the wrong size.)doc")
      .def("deformStale", [evaluate](py::object self, ffd::Lattice& lattice, const py::object& input) {
        return evaluate(self, lattice, input, &ffd::Deformer::deformStale);
      }, "lattice"_a, "input"_a, R"doc(Evaluates every point with an embedding whose rest lattice has moved since.

out = input + s F.linear() sum B (P - Pbar) with the old (u,v,w) (Kuriyama 1996, sec. 6.3.2):
exact while the lattice is at rest, an approximation otherwise.
Args:
    lattice: a lattice with the embedding's counts.
    input: N x 3 world points.
Raises:
    LatticeError: other counts, or input has the wrong size.)doc")
      .def("update",
           [evaluate](py::object self, ffd::Lattice& lattice, const py::object& input) {
             if (!input.is_none()) {
               using Ref = const Eigen::Ref<const Eigen::MatrixX3d>&;
               return evaluate(self, lattice, input, py::overload_cast<const ffd::Lattice&, Ref>(&ffd::Deformer::update));
             }
             auto& deformer = self.cast<ffd::Deformer&>();
             synced(lattice);
             withoutGil(PythonProgress(py::none()), [&] { return &deformer.update(lattice); });
             return viewOf(deformer.points(), self, false);
           },
           "lattice"_a, "input"_a = py::none(), R"doc(Re-evaluates only the points whose cells hold a control point changed since the last call.

Args:
    lattice: the lattice the embedding was built for.
    input: the N x 3 points that were embedded (exact, bit-identical to deform()); None adds
        the control-point changes to the previous output instead (faster; rounding accumulates).
Returns:
    N x 3 deformed world points (a read-only view).
Raises:
    LatticeError: a stale embedding, input of the wrong size, or deform() never called.)doc")
      .def_property_readonly("points", [](py::object self) {
        return viewOf(self.cast<const ffd::Deformer&>().points(), self, false);
      })
      .def_property_readonly("lastStats", &ffd::Deformer::lastStats)
      .def_property("precision", &ffd::Deformer::precision, &ffd::Deformer::setPrecision,
                    "Precision of the following calls; change it only before a deform().")
      .def("setParallel", &ffd::Deformer::setParallel, "parallel"_a, R"doc(Runs the following calls on all OpenMP threads (True, the default) or on this thread only.

Args:
    parallel: bool.)doc");
}


}  // namespace

void bindFfd(py::module_& module) {
  bindLattice(module);
  bindDeformation(module);
  bindFfdPipeline(module);
}

}  // namespace ffdkit::python
