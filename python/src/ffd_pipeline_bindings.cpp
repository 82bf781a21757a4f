// ffdkit.ffd, continued: pipelines of lattices and direct manipulation. Names mirror the C++ API
// (ffd/include/ffdkit/ffd/pipeline.h, direct_manipulation.h); see docs/python.md.

#include <string>

#include <pybind11/eigen.h>
#include <pybind11/operators.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "ffd_binding_support.h"
#include "ffdkit/ffd/direct_manipulation.h"
#include "ffdkit/ffd/lattice.h"
#include "ffdkit/ffd/pipeline.h"
#include "numpy_eigen.h"

namespace ffdkit::python {

using namespace pybind11::literals;

namespace {

void bindPipeline(py::module_& m) {
  py::class_<ffd::LatticeId>(m, "LatticeId", R"doc(The handle of a lattice in a Pipeline.

Returned by Pipeline.addLattice; field value (-1: none). Hashable and comparable.)doc")
      .def_readonly("value", &ffd::LatticeId::value)
      .def(py::self == py::self)
      .def("__hash__", [](const ffd::LatticeId& id) { return std::hash<int>{}(id.value); })
      .def("__repr__", [](const ffd::LatticeId& id) { return "LatticeId(" + std::to_string(id.value) + ")"; });

  py::class_<ffd::ReembedThrottle> throttle(m, "ReembedThrottle", R"doc(When lattices other than the active one re-embed after their input moved (Kuriyama 1996, sec. 6.3.2).

ReembedThrottle.immediate(), .everyN(n) or .onDemand(); between re-embeddings a stale lattice
deforms with its old (u,v,w) (Deformer.deformStale).)doc");
  py::enum_<ffd::ReembedThrottle::Kind>(throttle, "Kind", R"doc(The kind of throttle.

Immediate (every update), EveryN (every n-th update that finds the lattice stale) or OnDemand
(only in Pipeline.reembedAll()).)doc")
      .value("Immediate", ffd::ReembedThrottle::Kind::Immediate)
      .value("EveryN", ffd::ReembedThrottle::Kind::EveryN)
      .value("OnDemand", ffd::ReembedThrottle::Kind::OnDemand);
  throttle.def_readonly("kind", &ffd::ReembedThrottle::kind)
      .def_readonly("n", &ffd::ReembedThrottle::n)
      .def_static("immediate", &ffd::ReembedThrottle::immediate, R"doc(Re-embed on every update (exact, slowest).

Returns:
    ReembedThrottle.)doc")
      .def_static("everyN", &ffd::ReembedThrottle::everyN, "n"_a, R"doc(Re-embed on every n-th update that finds the lattice stale.

Args:
    n: >= 1.
Returns:
    ReembedThrottle.)doc")
      .def_static("onDemand", &ffd::ReembedThrottle::onDemand, R"doc(Re-embed only in Pipeline.reembedAll() (e.g. when a gesture ends).

Returns:
    ReembedThrottle.)doc");

  py::class_<ffd::StageReport>(m, "StageReport", R"doc(What one lattice of a Pipeline did in the last update.

Fields: id, reembedded, approximate (deformed with a stale embedding), outputChanged,
embedSeconds.)doc")
      .def_readonly("id", &ffd::StageReport::id)
      .def_readonly("reembedded", &ffd::StageReport::reembedded)
      .def_readonly("approximate", &ffd::StageReport::approximate)
      .def_readonly("outputChanged", &ffd::StageReport::outputChanged)
      .def_readonly("embedSeconds", &ffd::StageReport::embedSeconds);

  auto run = [](py::object self, bool reembedAll, const py::object& progress) {
    auto& pipeline = self.cast<ffd::Pipeline&>();
    for (const ffd::LatticeId id : pipeline.order()) synced(pipeline.lattice(id));
    PythonProgress hook(progress);
    withoutGil(hook, [&] {
      return reembedAll ? &pipeline.reembedAll(hook.embedHook()) : &pipeline.update(hook.embedHook());
    });
    return viewOf(pipeline.points(), self, false);
  };
  py::class_<ffd::Pipeline>(m, "Pipeline", R"doc(A tree of lattices deforming one point set, parents before children (ffd/pipeline.h).

Each lattice deforms the output of the one before it in pre-order (Kuriyama 1996, secs. 6.2.3,
6.3.2). update() re-embeds and re-evaluates only what changed; points is a read-only view.)doc")
      .def(py::init([](const py::object& points, const py::object& options) {
             return ffd::Pipeline(PointsArg(points, "points").ref(),
                                  options.is_none() ? ffd::EmbedOptions{} : options.cast<ffd::EmbedOptions>());
           }),
           "points"_a, "options"_a = py::none(), R"doc(A pipeline over a point set, with no lattice yet.

Args:
    points: N x 3 world points.
    options: EmbedOptions for every embedding (default: EmbedOptions()).
Raises:
    LatticeError: non-finite points. ValueError: points not N x 3.)doc")
      .def("addLattice", &ffd::Pipeline::addLattice, "lattice"_a, "parent"_a = py::none(), "priority"_a = 0, R"doc(Adds a copy of a lattice to the tree; edit it through lattice(id).

Args:
    lattice: the lattice.
    parent: LatticeId of its parent, or None for a root.
    priority: order among siblings (lower first).
Returns:
    LatticeId.
Raises:
    LatticeError: an unknown parent.)doc")
      .def("removeLattice", &ffd::Pipeline::removeLattice, "id"_a, R"doc(Removes a lattice and its whole subtree.

Args:
    id: LatticeId.
Raises:
    LatticeError: an unknown id.)doc")
      .def("setPriority", &ffd::Pipeline::setPriority, "id"_a, "priority"_a, R"doc(Changes a lattice's order among its siblings.

Args:
    id: LatticeId.
    priority: lower runs first.
Raises:
    LatticeError: an unknown id.)doc")
      .def("lattice", py::overload_cast<ffd::LatticeId>(&ffd::Pipeline::lattice),
           py::return_value_policy::reference_internal, "id"_a, R"doc(The pipeline's own lattice `id`, editable in place.

Args:
    id: LatticeId.
Returns:
    Lattice (a reference into the pipeline).
Raises:
    LatticeError: an unknown id.)doc")
      .def("setLattice", &ffd::Pipeline::setLattice, "id"_a, "lattice"_a, R"doc(Replaces lattice `id`.

Args:
    id: LatticeId.
    lattice: the new lattice.
Raises:
    LatticeError: an unknown id.)doc")
      .def("parent", &ffd::Pipeline::parent, "id"_a, R"doc(The parent of lattice `id`.

Args:
    id: LatticeId.
Returns:
    LatticeId, or None for a root.
Raises:
    LatticeError: an unknown id.)doc")
      .def("order", &ffd::Pipeline::order, R"doc(The lattices in evaluation order (pre-order: parents before children).

Returns:
    list of LatticeId.)doc")
      .def("setPoints",
           [](ffd::Pipeline& p, const py::object& points) { p.setPoints(PointsArg(points, "points").ref()); },
           "points"_a, R"doc(Replaces the object points; every lattice re-embeds at the next update.

Args:
    points: M x 3 world points (any count).
Raises:
    ValueError: not M x 3.)doc")
      .def("setActiveLattice", &ffd::Pipeline::setActiveLattice, "id"_a, R"doc(Marks the lattice being edited: it always re-embeds at once, the others follow the throttle.

Args:
    id: LatticeId, or None.)doc")
      .def("setThrottle", &ffd::Pipeline::setThrottle, "throttle"_a, R"doc(Sets when lattices other than the active one re-embed.

Args:
    throttle: ReembedThrottle (default immediate()).)doc")
      .def_property_readonly("throttle", &ffd::Pipeline::throttle)
      .def_property("precision", &ffd::Pipeline::precision, &ffd::Pipeline::setPrecision,
                    "Precision of every stage; a change evaluates the embedded stages in full at the next run.")
      .def("update", [run](py::object self, const py::object& progress) { return run(self, false, progress); },
           "progress"_a = py::none(), R"doc(Runs the pipeline: re-embeds and re-evaluates the lattices whose input or lattice changed.

Args:
    progress: callable(done, total), as for ffd.embed().
Returns:
    N x 3 deformed points (a read-only view). The interpreter lock is released while it runs.
Raises:
    LatticeError: a lattice that cannot embed. Cancelled: progress returned False.)doc")
      .def("reembedAll", [run](py::object self, const py::object& progress) { return run(self, true, progress); },
           "progress"_a = py::none(), R"doc(Re-embeds every lattice and evaluates the whole tree exactly.

Args:
    progress: callable(done, total), as for ffd.embed().
Returns:
    N x 3 deformed points (a read-only view).
Raises:
    LatticeError, Cancelled: as update().)doc")
      .def("pointsToEmbed", &ffd::Pipeline::pointsToEmbed, "reembedAll"_a = false, R"doc(How many points the next update() (or reembedAll()) would embed.

Args:
    reembedAll: count for reembedAll() instead.
Returns:
    int.)doc")
      .def_property_readonly("points", [](py::object self) {
        return viewOf(self.cast<const ffd::Pipeline&>().points(), self, false);
      })
      .def_property_readonly("inputPoints", [](py::object self) {
        return viewOf(self.cast<const ffd::Pipeline&>().inputPoints(), self, false);
      })
      .def("embedding", &ffd::Pipeline::embedding, py::return_value_policy::reference_internal, "id"_a, R"doc(The embedding of lattice `id` (None before its first update).

Args:
    id: LatticeId.
Raises:
    LatticeError: an unknown id.)doc")
      .def("lastReport", &ffd::Pipeline::lastReport, R"doc(What each lattice did in the last update.

Returns:
    list of StageReport, in evaluation order.)doc");
}

void bindDirectManipulation(py::module_& m) {
  py::class_<ffd::BasisWeight>(m, "BasisWeight", R"doc(One control point's basis weight at a parameter.

Fields: point (flat index), weight (B_ijk(u,v,w)).)doc")
      .def_readonly("point", &ffd::BasisWeight::point)
      .def_readonly("weight", &ffd::BasisWeight::weight);
  m.def("basisWeights", [](ffd::Lattice& l, const Eigen::Vector3d& uvw) { return ffd::basisWeights(l, uvw); },
        "lattice"_a, "uvw"_a, R"doc(The control points that influence parameter uvw, with their basis weights.

Args:
    lattice: the lattice.
    uvw: three parameters.
Returns:
    list of BasisWeight (weights sum to 1 inside the box).)doc");
  m.def("leastNormControlChange",
        [](ffd::Lattice& lattice, const py::object& uvw, const py::object& displacements) {
          synced(lattice);
          return toArray(ffd::leastNormControlChange(lattice, PointsArg(uvw, "uvw").ref(),
                                                     PointsArg(displacements, "displacements").ref()));
        },
        "lattice"_a, "uvw"_a, "displacements"_a, R"doc(The least-norm control-point change that moves the points at uvw by displacements (Hsu, Hughes & Kaufman 1992).

Args:
    lattice: the lattice.
    uvw: k x 3 parameters of the points to move.
    displacements: k x 3 lattice-local moves.
Returns:
    pointCount x 3 control-point change, lattice-local (add it to controlPoints).
Raises:
    ValueError: arrays not k x 3 or of different lengths.)doc");
}

}  // namespace

void bindFfdPipeline(py::module_& module) {
  bindPipeline(module);
  bindDirectManipulation(module);
}

}  // namespace ffdkit::python
