// ffdkit.ffd: lattices, embedding, deformation, pipelines and direct manipulation.
// Names mirror the C++ API (ffd/include/ffdkit/ffd/*.h); see docs/python.md.

#include <memory>
#include <string>
#include <utility>

#include <pybind11/eigen.h>
#include <pybind11/operators.h>
#include <pybind11/stl.h>

#include "bindings.h"
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

// The control points of a Python-side lattice are a writable numpy view: writes through it do
// not pass Lattice::setControlPoints, so every call that reads them first validates them and
// bumps the revision (a copy of l*m*n points, negligible beside any evaluation).
ffd::Lattice& synced(ffd::Lattice& lattice) {
  lattice.setControlPoints(Eigen::MatrixX3d(lattice.controlPoints()));
  return lattice;
}

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

// Runs `work` without the GIL; a Python exception raised by the progress callback replaces
// the Cancelled it caused.
template <typename Work>
auto withoutGil(const PythonProgress& progress, Work&& work) {
  try {
    py::gil_scoped_release release;
    return work();
  } catch (const ffd::Cancelled&) {
    progress.rethrowIfFailed();
    throw;
  }
}

void bindLattice(py::module_& m) {
  py::class_<ffd::AxisBasis> basis(m, "AxisBasis", "The basis of one lattice axis (ffd/axis_basis.h).");
  py::enum_<ffd::AxisBasis::Kind>(basis, "Kind")
      .value("Bernstein", ffd::AxisBasis::Kind::Bernstein)
      .value("BSpline", ffd::AxisBasis::Kind::BSpline)
      .value("PeriodicBSpline", ffd::AxisBasis::Kind::PeriodicBSpline);
  basis.def(py::init<>())
      .def_readwrite("kind", &ffd::AxisBasis::kind)
      .def_readwrite("degree", &ffd::AxisBasis::degree)
      .def_readwrite("knots", &ffd::AxisBasis::knots)
      .def_static("bernstein", &ffd::AxisBasis::bernstein)
      .def_static("bspline", &ffd::AxisBasis::bspline, "degree"_a = 3)
      .def_static("bsplineWithKnots", &ffd::AxisBasis::bsplineWithKnots, "degree"_a, "knots"_a)
      .def_static("periodic", &ffd::AxisBasis::periodic, "degree"_a = 3)
      .def("__repr__", &basisRepr);

  py::class_<ffd::OutsidePolicy> policy(m, "OutsidePolicy", "What happens to points outside the rest lattice.");
  py::enum_<ffd::OutsidePolicy::Kind>(policy, "Kind")
      .value("Identity", ffd::OutsidePolicy::Kind::Identity)
      .value("ClampEdge", ffd::OutsidePolicy::Kind::ClampEdge)
      .value("Extrapolate", ffd::OutsidePolicy::Kind::Extrapolate)
      .value("Falloff", ffd::OutsidePolicy::Kind::Falloff);
  policy.def(py::init<>())
      .def_readwrite("kind", &ffd::OutsidePolicy::kind)
      .def_readwrite("distance", &ffd::OutsidePolicy::distance)
      .def_static("identity", &ffd::OutsidePolicy::identity)
      .def_static("clampEdge", &ffd::OutsidePolicy::clampEdge)
      .def_static("extrapolate", &ffd::OutsidePolicy::extrapolate)
      .def_static("falloff", &ffd::OutsidePolicy::falloff, "distance"_a)
      .def(py::self == py::self)
      .def("__repr__", [](const ffd::OutsidePolicy& p) {
        return "OutsidePolicy(" + std::string(py::str(py::cast(p.kind))) + ", distance=" + std::to_string(p.distance) + ")";
      });

  py::class_<ffd::Lattice>(m, "Lattice",
                           "An FFD lattice of l x m x n control points (ffd/lattice.h). Control points are "
                           "lattice-local, one per row, flat index i + l*(j + m*k); world = frame @ local.")
      .def(py::init([](const Eigen::Vector3i& counts, const py::object& bases, const py::object& restPoints,
                       const py::object& frame) {
             const PointsArg rest(restPoints, "restPoints");
             return ffd::Lattice(counts, basesArg(bases, ffd::AxisBasis::bernstein()), rest.ref(),
                                 affineArg(frame, "frame"));
           }),
           "counts"_a, "bases"_a, "restPoints"_a, "frame"_a = py::none())
      .def_property_readonly("counts", &ffd::Lattice::counts)
      .def_property_readonly("pointCount", &ffd::Lattice::pointCount)
      .def("index", [](const ffd::Lattice& l, int i, int j, int k) {
        const Eigen::Vector3i c = l.counts();
        if (i < 0 || j < 0 || k < 0 || i >= c[0] || j >= c[1] || k >= c[2]) {
          throw py::index_error("index (" + std::to_string(i) + ", " + std::to_string(j) + ", " + std::to_string(k) +
                                ") is outside the lattice grid");
        }
        return l.index(i, j, k);
      }, "i"_a, "j"_a, "k"_a)
      .def("gridIndex", &ffd::Lattice::gridIndex, "flat"_a)
      .def("basis", [](const ffd::Lattice& l, int axis) { return l.basis(axis); }, "axis"_a)
      .def("knots", [](const ffd::Lattice& l, int axis) { return l.axis(axis).knots(); }, "axis"_a,
           "The resolved knot vector of an axis (Bernstein: count zeros, count ones).")
      .def("greville", [](const ffd::Lattice& l, int axis) { return l.axis(axis).greville(); }, "axis"_a)
      .def("degree", [](const ffd::Lattice& l, int axis) { return l.axis(axis).degree(); }, "axis"_a)
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
           "points"_a)
      .def("setControlPoint", &ffd::Lattice::setControlPoint, "flat"_a, "point"_a)
      .def("resetToRest", &ffd::Lattice::resetToRest)
      .def("setRestPoints",
           [](ffd::Lattice& l, const py::object& points) { l.setRestPoints(PointsArg(points, "restPoints").ref()); },
           "restPoints"_a)
      .def_property("frame", [](const ffd::Lattice& l) { return affineToArray(l.frame()); },
                    [](ffd::Lattice& l, const py::object& f) { l.setFrame(affineArg(f, "frame")); })
      .def("setFrame", [](ffd::Lattice& l, const py::object& f) { l.setFrame(affineArg(f, "frame")); }, "frame"_a)
      .def_property("outsidePolicy", &ffd::Lattice::outsidePolicy, &ffd::Lattice::setOutsidePolicy)
      .def("setOutsidePolicy", &ffd::Lattice::setOutsidePolicy, "policy"_a)
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
           "uvw"_a, "X(u,v,w) (Kuriyama 1996, eq. (6.1)) for each row of uvw (N x 3), lattice-local.")
      .def("evaluateRest",
           [](const ffd::Lattice& l, const py::object& uvw) {
             const PointsArg parameters(uvw, "uvw");
             Eigen::MatrixX3d out(parameters.rows(), 3);
             for (Eigen::Index r = 0; r < out.rows(); ++r) {
               out.row(r) = l.evaluateRest(parameters.ref().row(r).transpose()).transpose();
             }
             return toArray(std::move(out));
           },
           "uvw"_a)
      .def("jacobian", [](ffd::Lattice& l, const Eigen::Vector3d& uvw) { return synced(l).jacobian(uvw); }, "uvw"_a)
      .def_property_readonly("restIsAffine", &ffd::Lattice::restIsAffine)
      .def_property_readonly("restSize", &ffd::Lattice::restSize)
      .def("copy", [](const ffd::Lattice& l) { return ffd::Lattice(l); })
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
        "outsidePolicy"_a = ffd::OutsidePolicy{}, "capDegreeToCount"_a = true,
        "A box lattice (BoxLatticeOptions as keywords); bases default to cubic B-splines.");
  m.def("makeLattice",
        [](const Eigen::Vector3i& counts, const py::object& bases, const py::object& restPoints, const py::object& frame) {
          return ffd::makeLattice(counts, basesArg(bases, ffd::AxisBasis::bernstein()),
                                  PointsArg(restPoints, "restPoints").ref(), affineArg(frame, "frame"));
        },
        "counts"_a, "bases"_a, "restPoints"_a, "frame"_a = py::none(), "A user-shaped lattice.");
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
        "zMin"_a = 0.0, "zMax"_a = 1.0, "frame"_a = py::none(), "outsidePolicy"_a = ffd::OutsidePolicy{},
        "An EFFD cylindrical lattice (CylindricalLatticeOptions as keywords).");

  m.def("bernsteinBasis", &ffd::bernsteinBasis, "degree"_a, "t"_a);
  m.def("clampedUniformKnots", &ffd::clampedUniformKnots, "count"_a, "degree"_a);
  m.def("periodicUniformKnots", &ffd::periodicUniformKnots, "count"_a, "degree"_a);
  m.def("grevilleAbscissae", &ffd::grevilleAbscissae, "knots"_a, "count"_a, "degree"_a);
}

void bindDeformation(py::module_& m) {
  py::enum_<ffd::PointStatus>(m, "PointStatus")
      .value("Inside", ffd::PointStatus::Inside)
      .value("Outside", ffd::PointStatus::Outside)
      .value("Failed", ffd::PointStatus::Failed);

  py::class_<ffd::EmbedOptions>(m, "EmbedOptions")
      .def(py::init([](double tolerance, int maxIterations, double boundaryEpsilon, bool parallel) {
             ffd::EmbedOptions options;
             options.tolerance = tolerance;
             options.maxIterations = maxIterations;
             options.boundaryEpsilon = boundaryEpsilon;
             options.parallel = parallel;
             return options;
           }),
           "tolerance"_a = 1e-13, "maxIterations"_a = 40, "boundaryEpsilon"_a = 1e-9, "parallel"_a = true,
           "Embedding options; the progress hook is the `progress` argument of embed() and Pipeline.update().")
      .def_readwrite("tolerance", &ffd::EmbedOptions::tolerance)
      .def_readwrite("maxIterations", &ffd::EmbedOptions::maxIterations)
      .def_readwrite("boundaryEpsilon", &ffd::EmbedOptions::boundaryEpsilon)
      .def_readwrite("parallel", &ffd::EmbedOptions::parallel);
  m.attr("kEmbedProgressChunk") = ffd::kEmbedProgressChunk;

  py::class_<ffd::Embedding>(m, "Embedding", "The (u,v,w) of a point set in one lattice (ffd/embedding.h).")
      .def_property_readonly("pointCount", &ffd::Embedding::pointCount)
      .def("status", &ffd::Embedding::status, "point"_a)
      .def("statuses",
           [](py::object self) {
             const auto& statuses = self.cast<const ffd::Embedding&>().statuses();
             py::array view(py::dtype::of<std::uint8_t>(), {static_cast<py::ssize_t>(statuses.size())},
                            {py::ssize_t(1)}, reinterpret_cast<const std::uint8_t*>(statuses.data()), self);
             py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
             return view;
           },
           "Per-point status codes (uint8: 0 Inside, 1 Outside, 2 Failed; int(PointStatus.X)), a read-only view.")
      .def_property_readonly("insideCount", &ffd::Embedding::insideCount)
      .def_property_readonly("outsideCount", &ffd::Embedding::outsideCount)
      .def_property_readonly("failedCount", &ffd::Embedding::failedCount)
      .def("parameters", [](const ffd::Embedding& e) { return toArray(e.parameters()); })
      .def_property_readonly("restRevision", &ffd::Embedding::restRevision)
      .def_property_readonly("latticeCounts", &ffd::Embedding::latticeCounts)
      .def_property_readonly("outsidePolicy", &ffd::Embedding::outsidePolicy)
      .def("checkLattice", &ffd::Embedding::checkLattice, "lattice"_a)
      .def("memoryBytes", &ffd::Embedding::memoryBytes);

  m.def("embed",
        [](const ffd::Lattice& lattice, const py::object& points, const py::object& options, const py::object& progress) {
          const PointsArg q(points, "points");
          const EmbedArgs args(options, progress);
          return withoutGil(args.progress, [&] { return ffd::embed(lattice, q.ref(), args.embed); });
        },
        "lattice"_a, "points"_a, "options"_a = py::none(), "progress"_a = py::none(),
        "Embeds WORLD points (N x 3) into the rest lattice (Kuriyama 1996, eq. (6.2)); the GIL is released. "
        "progress(done, total) -> bool|None is called on this thread; False or an exception cancels "
        "(ffdkit.Cancelled, or the exception itself).");

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
        "lattice"_a, "points"_a, "options"_a = py::none(), "progress"_a = py::none(),
        "One-shot FFD of a point set: embed (GIL released) then deform; returns a new writable (N, 3) array.");

  py::class_<ffd::DeformStats>(m, "DeformStats")
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
  py::enum_<ffd::Precision>(m, "Precision",
                            "Arithmetic of the deformation: Double (default) or Single (float32 displacements, "
                            "within 1e-6 of the largest control-point move; ffd/deformer.h).")
      .value("Double", ffd::Precision::Double)
      .value("Single", ffd::Precision::Single);
  py::class_<ffd::Deformer>(m, "Deformer", "Maps embedded points through a lattice (ffd/deformer.h).")
      .def(py::init<>())
      .def(py::init<ffd::Embedding>(), "embedding"_a, "Takes a copy of the embedding.")
      .def_static("fromPoints",
                  [](const ffd::Lattice& lattice, const py::object& points, const py::object& options,
                     const py::object& progress) {
                    const PointsArg q(points, "points");
                    const EmbedArgs args(options, progress);
                    return withoutGil(args.progress,
                                      [&] { return ffd::Deformer(ffd::embed(lattice, q.ref(), args.embed)); });
                  },
                  "lattice"_a, "points"_a, "options"_a = py::none(), "progress"_a = py::none(),
                  "Deformer(embed(lattice, points, options)) without copying the embedding.")
      .def_property_readonly("embedding", &ffd::Deformer::embedding, py::return_value_policy::reference_internal)
      .def("deform", [evaluate](py::object self, ffd::Lattice& lattice, const py::object& input) {
        return evaluate(self, lattice, input, &ffd::Deformer::deform);
      }, "lattice"_a, "input"_a, "Full evaluation; returns the deformed WORLD points (a read-only view).")
      .def("deformStale", [evaluate](py::object self, ffd::Lattice& lattice, const py::object& input) {
        return evaluate(self, lattice, input, &ffd::Deformer::deformStale);
      }, "lattice"_a, "input"_a)
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
           "lattice"_a, "input"_a = py::none(),
           "Incremental evaluation of the points whose cells hold a changed control point.")
      .def_property_readonly("points", [](py::object self) {
        return viewOf(self.cast<const ffd::Deformer&>().points(), self, false);
      })
      .def_property_readonly("lastStats", &ffd::Deformer::lastStats)
      .def_property("precision", &ffd::Deformer::precision, &ffd::Deformer::setPrecision,
                    "Precision of the following calls; change it only before a deform().")
      .def("setParallel", &ffd::Deformer::setParallel, "parallel"_a);
}

void bindPipeline(py::module_& m) {
  py::class_<ffd::LatticeId>(m, "LatticeId")
      .def_readonly("value", &ffd::LatticeId::value)
      .def(py::self == py::self)
      .def("__hash__", [](const ffd::LatticeId& id) { return std::hash<int>{}(id.value); })
      .def("__repr__", [](const ffd::LatticeId& id) { return "LatticeId(" + std::to_string(id.value) + ")"; });

  py::class_<ffd::ReembedThrottle> throttle(m, "ReembedThrottle");
  py::enum_<ffd::ReembedThrottle::Kind>(throttle, "Kind")
      .value("Immediate", ffd::ReembedThrottle::Kind::Immediate)
      .value("EveryN", ffd::ReembedThrottle::Kind::EveryN)
      .value("OnDemand", ffd::ReembedThrottle::Kind::OnDemand);
  throttle.def_readonly("kind", &ffd::ReembedThrottle::kind)
      .def_readonly("n", &ffd::ReembedThrottle::n)
      .def_static("immediate", &ffd::ReembedThrottle::immediate)
      .def_static("everyN", &ffd::ReembedThrottle::everyN, "n"_a)
      .def_static("onDemand", &ffd::ReembedThrottle::onDemand);

  py::class_<ffd::StageReport>(m, "StageReport")
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
  py::class_<ffd::Pipeline>(m, "Pipeline", "A tree of lattices deforming one point set in pre-order (ffd/pipeline.h).")
      .def(py::init([](const py::object& points, const py::object& options) {
             return ffd::Pipeline(PointsArg(points, "points").ref(),
                                  options.is_none() ? ffd::EmbedOptions{} : options.cast<ffd::EmbedOptions>());
           }),
           "points"_a, "options"_a = py::none())
      .def("addLattice", &ffd::Pipeline::addLattice, "lattice"_a, "parent"_a = py::none(), "priority"_a = 0,
           "Adds a copy of the lattice; edit it through lattice(id).")
      .def("removeLattice", &ffd::Pipeline::removeLattice, "id"_a)
      .def("setPriority", &ffd::Pipeline::setPriority, "id"_a, "priority"_a)
      .def("lattice", py::overload_cast<ffd::LatticeId>(&ffd::Pipeline::lattice),
           py::return_value_policy::reference_internal, "id"_a)
      .def("setLattice", &ffd::Pipeline::setLattice, "id"_a, "lattice"_a)
      .def("parent", &ffd::Pipeline::parent, "id"_a)
      .def("order", &ffd::Pipeline::order)
      .def("setPoints",
           [](ffd::Pipeline& p, const py::object& points) { p.setPoints(PointsArg(points, "points").ref()); },
           "points"_a)
      .def("setActiveLattice", &ffd::Pipeline::setActiveLattice, "id"_a)
      .def("setThrottle", &ffd::Pipeline::setThrottle, "throttle"_a)
      .def_property_readonly("throttle", &ffd::Pipeline::throttle)
      .def_property("precision", &ffd::Pipeline::precision, &ffd::Pipeline::setPrecision,
                    "Precision of every stage; a change evaluates the embedded stages in full at the next run.")
      .def("update", [run](py::object self, const py::object& progress) { return run(self, false, progress); },
           "progress"_a = py::none(), "Runs the pipeline (GIL released); returns the deformed points (read-only view).")
      .def("reembedAll", [run](py::object self, const py::object& progress) { return run(self, true, progress); },
           "progress"_a = py::none())
      .def("pointsToEmbed", &ffd::Pipeline::pointsToEmbed, "reembedAll"_a = false)
      .def_property_readonly("points", [](py::object self) {
        return viewOf(self.cast<const ffd::Pipeline&>().points(), self, false);
      })
      .def_property_readonly("inputPoints", [](py::object self) {
        return viewOf(self.cast<const ffd::Pipeline&>().inputPoints(), self, false);
      })
      .def("embedding", &ffd::Pipeline::embedding, py::return_value_policy::reference_internal, "id"_a)
      .def("lastReport", &ffd::Pipeline::lastReport);
}

void bindDirectManipulation(py::module_& m) {
  py::class_<ffd::BasisWeight>(m, "BasisWeight")
      .def_readonly("point", &ffd::BasisWeight::point)
      .def_readonly("weight", &ffd::BasisWeight::weight);
  m.def("basisWeights", [](ffd::Lattice& l, const Eigen::Vector3d& uvw) { return ffd::basisWeights(l, uvw); },
        "lattice"_a, "uvw"_a);
  m.def("leastNormControlChange",
        [](ffd::Lattice& lattice, const py::object& uvw, const py::object& displacements) {
          synced(lattice);
          return toArray(ffd::leastNormControlChange(lattice, PointsArg(uvw, "uvw").ref(),
                                                     PointsArg(displacements, "displacements").ref()));
        },
        "lattice"_a, "uvw"_a, "displacements"_a,
        "Hsu, Hughes & Kaufman 1992: the least-norm control change (pointCount x 3) moving the points at uvw "
        "(k x 3) by displacements (k x 3, lattice-local).");
}

}  // namespace

void bindFfd(py::module_& module) {
  bindLattice(module);
  bindDeformation(module);
  bindPipeline(module);
  bindDirectManipulation(module);
}

}  // namespace ffdkit::python
