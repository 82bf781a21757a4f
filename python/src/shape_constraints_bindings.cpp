// ffdkit.ffd: shape constraints (linear rows, barycentre, centroid, enclosed volume) and the
// certified fold-over bound. Names mirror ffd/shape_constraints.h, ffd/closed_surface.h and
// ffd/fold_check.h; see docs/python.md.

#include <string>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "ffdkit/ffd/closed_surface.h"
#include "ffdkit/ffd/fold_check.h"
#include "ffdkit/ffd/shape_constraints.h"
#include "ffd_binding_support.h"
#include "numpy_eigen.h"

namespace ffdkit::python {

using namespace pybind11::literals;

namespace {

ffd::ClosedSurface surfaceArg(const py::handle& triangles, Eigen::Index vertices) {
  const Eigen::MatrixX3i rows = intRows3(triangles, "triangles");
  return ffd::ClosedSurface(ffd::TriangleMatrix(rows), vertices);
}

const char* foldingName(ffd::CellFolding f) {
  switch (f) {
    case ffd::CellFolding::Positive: return "positive";
    case ffd::CellFolding::Folds: return "folds";
    case ffd::CellFolding::Unknown: return "unknown";
  }
  return "unknown";
}

}  // namespace

void bindShapeConstraints(py::module_& m) {
  m.def("enclosedVolume",
        [](const py::object& points, const py::object& triangles) {
          PointsArg p(points, "points");
          return ffd::enclosedVolume(p.ref(), surfaceArg(triangles, p.rows()));
        },
        "points"_a, "triangles"_a, R"doc(The volume a closed triangle surface bounds (divergence theorem).

Args:
    points: (N, 3) vertices.
    triangles: (T, 3) vertex indices, counter-clockwise seen from outside.

Raises:
    ConstraintError: the surface is open, misoriented, or an index is out of range (the message
        names the edge and the triangle).)doc");
  m.def("enclosedCentroid",
        [](const py::object& points, const py::object& triangles) {
          PointsArg p(points, "points");
          return Eigen::Vector3d(ffd::enclosedCentroid(p.ref(), surfaceArg(triangles, p.rows())));
        },
        "points"_a, "triangles"_a, R"doc(The centroid of the solid a closed triangle surface bounds.

Args:
    points: (N, 3) vertices.
    triangles: (T, 3) vertex indices, counter-clockwise seen from outside.

Raises:
    ConstraintError: an open or misoriented surface, or a zero volume.)doc");

  py::class_<ffd::ShapeSolveResult>(m, "ShapeSolveResult", R"doc(What ShapeConstraints.solve() did.

change is the (N, 3) lattice-local control change; iterations the Newton steps; volume and
volumeRelativeError the kept volume after the change.)doc")
      .def_property_readonly("change", [](const ffd::ShapeSolveResult& r) { return Eigen::MatrixX3d(r.change); },
                             "(N, 3) lattice-local control change: add it to lattice.controlPoints.")
      .def_readonly("iterations", &ffd::ShapeSolveResult::iterations, "Newton steps taken (0: already met).")
      .def_readonly("volume", &ffd::ShapeSolveResult::volume, "The enclosed volume after the change.")
      .def_readonly("volumeRelativeError", &ffd::ShapeSolveResult::volumeRelativeError, "|V - V*| / |V*| after the change.")
      .def_readonly("largestRelativeResidual", &ffd::ShapeSolveResult::largestRelativeResidual,
                    "The largest scaled residual over all constraints.")
      .def_readonly("lastStep", &ffd::ShapeSolveResult::lastStep,
                    "Relative size of the last Newton step's change of the control change.");

  py::class_<ffd::ShapeConstraints>(m, "ShapeConstraints", R"doc(Constraints on the deformed shape of points in one lattice (ffd/shape_constraints.h).

The solve finds the least-norm control change (lattice-local, over the free control coordinates)
that meets every constraint: linear rows A x' = b over the deformed world points, the mean of the
points, the centroid or the volume of a closed surface over them. Nonlinear constraints are met by
Newton on the Lagrange system to a relative error of 1e-12.

    c = ffd.ShapeConstraints(lattice, points)
    c.keepVolume(triangles, ffd.enclosedVolume(points, triangles))
    # ... move control points ...
    r = c.solve(lattice)
    lattice.setControlPoints(lattice.controlPoints + r.change)
)doc")
      .def(py::init([](ffd::Lattice& lattice, const py::object& points, const py::object& options) {
             PointsArg p(points, "points");
             ffd::EmbedOptions embed;
             if (!options.is_none()) embed = options.cast<ffd::EmbedOptions>();
             return ffd::ShapeConstraints(synced(lattice), p.ref(), embed);
           }),
           "lattice"_a, "points"_a, "embedOptions"_a = py::none(), R"doc(Embeds the (N, 3) world points in the lattice's rest lattice.

Args:
    lattice: the lattice whose control points solve() will change.
    points: (N, 3) world points before deformation.
    embedOptions: EmbedOptions, or None for the defaults.)doc")
      .def_property_readonly("pointCount", &ffd::ShapeConstraints::pointCount)
      .def("setFreeControls",
           [](ffd::ShapeConstraints& c, const Eigen::Matrix<bool, Eigen::Dynamic, 3>& free) { c.setFreeControls(free); },
           "free"_a, R"doc(Restricts the solve to some control coordinates.

Args:
    free: (controlPointCount, 3) bool, True = may move (columns: lattice-local axes).)doc")
      .def("addLinear",
           [](ffd::ShapeConstraints& c, const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
             c.addLinear(A.sparseView(), b);
           },
           "A"_a, "b"_a, R"doc(Adds linear rows A x' = b on the deformed world points.

Args:
    A: (m, 3N), columns over the points flattened by row (x0, y0, z0, x1, ...).
    b: (m,) right sides.)doc")
      .def("keepBarycentre", &ffd::ShapeConstraints::keepBarycentre, "target"_a,
           R"doc(Keeps the mean of the deformed points at `target`.

Args:
    target: (3,) world point; three linear rows.)doc")
      .def("keepVolume",
           [](ffd::ShapeConstraints& c, const py::object& triangles, double target, const std::string& evaluation) {
             ffd::VolumeEvaluation mode = ffd::VolumeEvaluation::Automatic;
             if (evaluation == "polynomial")
               mode = ffd::VolumeEvaluation::Polynomial;
             else if (evaluation == "per_vertex")
               mode = ffd::VolumeEvaluation::PerVertex;
             else if (evaluation != "automatic")
               throw py::value_error("keepVolume: evaluation must be 'automatic', 'polynomial' or 'per_vertex', got '" +
                                     evaluation + "'");
             c.keepVolume(surfaceArg(triangles, c.pointCount()), target, mode);
           },
           "triangles"_a, "target"_a, "evaluation"_a = "automatic",
           R"doc(Keeps the volume a closed surface over the points bounds.

Args:
    triangles: (T, 3) vertex indices into the points, counter-clockwise seen from outside.
    target: the volume (world units cubed), finite and non-zero.
    evaluation: 'polynomial' precomputes the volume as a cubic polynomial in the control points
        (one pass over the vertices) so that each Newton step costs O(lattice): for many solves
        (a drag); 'per_vertex' deforms and sums over the triangles in each step: for one solve;
        'automatic' (default) is 'polynomial' when at most 128 control points move the surface.

Raises:
    ConstraintError: the surface is open or misoriented (names the edge and triangle), or
        'polynomial' with more than 128 control points moving the surface.)doc")
      .def("keptVolume", [](const ffd::ShapeConstraints& c, ffd::Lattice& lattice) { return c.keptVolume(synced(lattice)); },
           "lattice"_a,
           R"doc(The volume the kept surface encloses once deformed by the lattice's control points.

Evaluated by the precomputed polynomial when keepVolume chose it (O(lattice)), else by deforming
the points and summing over the triangles; a drag's status line (the volume change) costs
nothing more than its solve.

Args:
    lattice: the lattice these constraints were built for (the one embedded).

Returns:
    The enclosed volume in world units cubed.

Raises:
    ConstraintError: keepVolume was not called.
    LatticeError: the lattice is not the one embedded.)doc")
      .def("keepCentroid",
           [](ffd::ShapeConstraints& c, const py::object& triangles, const Eigen::Vector3d& target) {
             c.keepCentroid(surfaceArg(triangles, c.pointCount()), target);
           },
           "triangles"_a, "target"_a, R"doc(Keeps the centroid of the solid a closed surface bounds.

Args:
    triangles: (T, 3) vertex indices into the points.
    target: (3,) world point.)doc")
      .def("solve",
           [](ffd::ShapeConstraints& c, ffd::Lattice& lattice, double tolerance, double stationarity, int maxIterations) {
             ffd::ShapeSolveOptions options;
             options.tolerance = tolerance;
             options.stationarity = stationarity;
             options.maxIterations = maxIterations;
             const ffd::Lattice& l = synced(lattice);
             py::gil_scoped_release release;
             return c.solve(l, options);
           },
           "lattice"_a, "tolerance"_a = 1e-12, "stationarity"_a = 1e-10, "maxIterations"_a = 40,
           R"doc(The least-norm control change meeting every constraint (the lattice is not changed).

Raises:
    ConstraintError: the constraints cannot be met with the free controls, or Newton did not
        converge. LatticeError: the lattice is not the one embedded.)doc")
      .def("deformedPoints", [](const ffd::ShapeConstraints& c) { return Eigen::MatrixX3d(c.deformedPoints()); },
           R"doc(The deformed points of the last solve, after its change.

Returns:
    (N, 3) world points.)doc");

  py::class_<ffd::FoldCheckResult>(m, "FoldCheckResult", R"doc(The fold-over verdict of every lattice cell (ffd/fold_check.h).

cells holds 'positive', 'folds' or 'unknown' per cell; witness a parameter point with
det J <= 0 for the cells that fold.)doc")
      .def_property_readonly("cellCounts", [](const ffd::FoldCheckResult& r) { return r.cellCounts; })
      .def_property_readonly("cells",
                             [](const ffd::FoldCheckResult& r) {
                               std::vector<std::string> out;
                               for (ffd::CellFolding f : r.cells) out.emplace_back(foldingName(f));
                               return out;
                             },
                             "Per cell (flat index cu + cells_u (cv + cells_v cw)): 'positive', 'folds' or 'unknown'.")
      .def_readonly("lowerBound", &ffd::FoldCheckResult::lowerBound, "Per cell, a lower bound of sign * det J.")
      .def_property_readonly("witness",
                             [](const ffd::FoldCheckResult& r) {
                               Eigen::MatrixX3d w(Eigen::Index(r.witness.size()), 3);
                               for (std::size_t i = 0; i < r.witness.size(); ++i) w.row(Eigen::Index(i)) = r.witness[i].transpose();
                               return w;
                             },
                             "(cells, 3): a parameter point where det J <= 0 for 'folds' cells, NaN otherwise.")
      .def_readonly("positiveCount", &ffd::FoldCheckResult::positiveCount)
      .def_readonly("foldsCount", &ffd::FoldCheckResult::foldsCount)
      .def_readonly("unknownCount", &ffd::FoldCheckResult::unknownCount)
      .def_readonly("orientation", &ffd::FoldCheckResult::orientation)
      .def("certifiedPositive", &ffd::FoldCheckResult::certifiedPositive, R"doc(True when every cell is certified positive.

No cell folds and none is unknown.)doc")
      .def("__repr__", [](const ffd::FoldCheckResult& r) {
        return "FoldCheckResult(positive=" + std::to_string(r.positiveCount) + ", folds=" + std::to_string(r.foldsCount) +
               ", unknown=" + std::to_string(r.unknownCount) + ")";
      });
  m.def("checkFolding",
        [](ffd::Lattice& lattice, int maxDepth) {
          ffd::FoldCheckOptions options;
          options.maxDepth = maxDepth;
          const ffd::Lattice& l = synced(lattice);
          py::gil_scoped_release release;
          return ffd::checkFolding(l, options);
        },
        "lattice"_a, "maxDepth"_a = 4, R"doc(A certified fold-over bound of the lattice's current control points.

Per cell, det J of the lattice map in Bernstein form: all coefficients > 0 certifies 'positive';
a point with det J <= 0 proves 'folds'; otherwise the cell is split (de Casteljau) down to
maxDepth halvings and what stays inconclusive is 'unknown'.)doc");
  m.def("jacobianDeterminant",
        [](ffd::Lattice& lattice, const Eigen::Vector3d& uvw) {
          const ffd::Lattice& l = synced(lattice);
          const std::array<int, 3> cell = {l.axis(0).cellOf(uvw[0]), l.axis(1).cellOf(uvw[1]), l.axis(2).cellOf(uvw[2])};
          return ffd::jacobianDeterminantPatch(l, cell).value(uvw);
        },
        "lattice"_a, "uvw"_a, R"doc(det(dX/d(u,v,w)) at one parameter, from its cell's Bernstein patch.

Args:
    lattice: the lattice (its current control points).
    uvw: (3,) parameters.)doc");
}

}  // namespace ffdkit::python
