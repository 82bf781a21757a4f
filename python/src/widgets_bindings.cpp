// ffdkit.widgets: the headless widget model of Kuriyama 1996, ch. 6
// (widgets/include/ffdkit/widgets). Names mirror the C++ API; lattice points come back as numpy
// arrays (N x 3). Here the value types and WidgetModel's construction and edits; its queries are
// in widget_model_query_bindings.cpp, its gestures and drags in widget_model_gesture_bindings.cpp.

#include <string>
#include <utility>

#include <pybind11/eigen.h>
#include <pybind11/operators.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "widget_model_binding_support.h"
#include "ffdkit/widgets/widget_model.h"
#include "numpy_eigen.h"

namespace ffdkit::python {

using namespace pybind11::literals;
using widgets::WidgetId;
using widgets::WidgetModel;

namespace {

void bindValueTypes(py::module_& m) {
  py::class_<WidgetId>(m, "WidgetId", R"doc(The handle of a widget in one WidgetModel; printed as w<N>.

Returned by the add* calls and find(); hashable and ordered. value is the number; valid() is
False for a default-constructed id.)doc")
      .def_readonly("value", &WidgetId::value)
      .def("valid", &WidgetId::valid, R"doc(True unless the id is the invalid default.

Returns:
    bool.)doc")
      .def(py::self == py::self)
      .def(py::self < py::self)
      .def("__hash__", [](const WidgetId& id) { return std::hash<std::uint32_t>{}(id.value); })
      .def("__repr__", [](const WidgetId& id) { return widgets::toString(id); });
  py::class_<widgets::BindingId>(m, "BindingId", R"doc(The handle of a binding in one WidgetModel; printed as b<N>.

Returned by WidgetModel.bind(); hashable; field value.)doc")
      .def_readonly("value", &widgets::BindingId::value)
      .def(py::self == py::self)
      .def("__hash__", [](const widgets::BindingId& id) { return std::hash<std::uint32_t>{}(id.value); })
      .def("__repr__", [](const widgets::BindingId& id) { return widgets::toString(id); });

  py::enum_<widgets::WidgetType>(m, "WidgetType", R"doc(The type of a widget: Lattice, Cell or Affine.

WidgetModel.type(id) returns it; widgets(type) and names(type) filter by it.)doc")
      .value("Lattice", widgets::WidgetType::Lattice)
      .value("Cell", widgets::WidgetType::Cell)
      .value("Affine", widgets::WidgetType::Affine);
  py::enum_<widgets::AffineKind>(m, "AffineKind", R"doc(What an affine widget does: Translate (along its x), Rotate (about its z) or Scale.

Its variation is a distance, an angle in radians or a log scale factor.)doc")
      .value("Translate", widgets::AffineKind::Translate)
      .value("Rotate", widgets::AffineKind::Rotate)
      .value("Scale", widgets::AffineKind::Scale);
  py::enum_<widgets::CellKind>(m, "CellKind", R"doc(Which points a cell groups: Point, Edge, Face, Slab, Box or Custom (Kuriyama 1996, sec. 6.2.1).

CellSpec.point(...), .edge(...), ... make the specs.)doc")
      .value("Point", widgets::CellKind::Point)
      .value("Edge", widgets::CellKind::Edge)
      .value("Face", widgets::CellKind::Face)
      .value("Slab", widgets::CellKind::Slab)
      .value("Box", widgets::CellKind::Box)
      .value("Custom", widgets::CellKind::Custom);
  py::enum_<widgets::BindingKind>(m, "BindingKind", R"doc(The kind of a binding, decided by the two widgets bound (Kuriyama 1996, sec. 6.2.2).

Attachment (cell -> affine widget), Variation (affine -> affine, through a ConversionRule),
CellMotion (cell -> cell) or Hierarchy (cell -> lattice: the lattice rides on the cell).)doc")
      .value("Attachment", widgets::BindingKind::Attachment)
      .value("Variation", widgets::BindingKind::Variation)
      .value("CellMotion", widgets::BindingKind::CellMotion)
      .value("Hierarchy", widgets::BindingKind::Hierarchy);

  py::class_<widgets::AffineMask>(m, "AffineMask", R"doc(Which of translation, rotation and scale a binding carries.

AffineMask(translate=True, rotate=True, scale=False), or AffineMask.parse("TR"); str() gives
the letters.)doc")
      .def(py::init([](bool t, bool r, bool s) { return widgets::AffineMask{t, r, s}; }), "translate"_a = true,
           "rotate"_a = true, "scale"_a = false, R"doc(A mask from three flags.

Args:
    translate, rotate, scale: whether each part passes.)doc")
      .def_readwrite("translate", &widgets::AffineMask::translate)
      .def_readwrite("rotate", &widgets::AffineMask::rotate)
      .def_readwrite("scale", &widgets::AffineMask::scale)
      .def_static("parse", [](const std::string& text) {
        auto mask = widgets::parseMask(text);
        if (!mask) throw py::value_error("mask: expected letters T, R, S at most once each, got '" + text + "'");
        return *mask;
      }, "text"_a, R"doc(A mask from its letters, e.g. "TR" (translation and rotation).

Args:
    text: the letters T, R, S, each at most once ("" passes nothing).
Raises:
    ValueError: another letter, or one given twice.)doc")
      .def(py::self == py::self)
      .def("__str__", &widgets::maskString)
      .def("__repr__", [](const widgets::AffineMask& mask) { return "AffineMask('" + widgets::maskString(mask) + "')"; });

  py::class_<widgets::VariationRange>(m, "VariationRange", R"doc(A closed range of variation: a distance, an angle in radians or a log scale factor.

VariationRange(min, max); ConversionRule.clamp holds one.)doc")
      .def(py::init([](double lo, double hi) { return widgets::VariationRange{lo, hi}; }), "min"_a, "max"_a, R"doc(The range [min, max].

Args:
    min, max: its ends (an empty range is refused where it is used).)doc")
      .def_readwrite("min", &widgets::VariationRange::min)
      .def_readwrite("max", &widgets::VariationRange::max);
  py::class_<widgets::ConversionRule>(m, "ConversionRule", R"doc(The rule of an affine <-> affine binding: delta_to = gain * delta_from, optionally clamped.

ConversionRule(gain=1.0, clamp=None), or ConversionRule.screw(distancePerTurn). The clamp
bounds the driven widget's accumulated variation (Kuriyama 1996, sec. 6.2.2).)doc")
      .def(py::init<double, std::optional<widgets::VariationRange>>(), "gain"_a = 1.0, "clamp"_a = py::none(), R"doc(A conversion rule.

Args:
    gain: != 0 and finite (checked when the binding is made: WidgetError InvalidArgument).
    clamp: VariationRange bounding the driven widget's variation, or None.)doc")
      .def_readwrite("gain", &widgets::ConversionRule::gain)
      .def_readwrite("clamp", &widgets::ConversionRule::clamp)
      .def_static("screw", &widgets::ConversionRule::screw, "distancePerTurn"_a, R"doc(A screw: distancePerTurn of translation per full turn (2 pi rad) of a rotate widget.

Args:
    distancePerTurn: the pitch (Kuriyama 1996, Fig. 6-10), for a binding from a rotate widget to
        a translate widget.
Returns:
    ConversionRule with gain distancePerTurn / (2 pi).)doc")
      .def(py::self == py::self);

  py::class_<widgets::Binding>(m, "Binding", R"doc(One binding of a WidgetModel (read-only; WidgetModel.binding(id) returns it).

Fields: id, kind (BindingKind), from_ and to (WidgetId), mask (AffineMask), rule
(ConversionRule, Variation only), oneWay.)doc")
      .def_readonly("id", &widgets::Binding::id)
      .def_readonly("kind", &widgets::Binding::kind)
      .def_readonly("from_", &widgets::Binding::from)
      .def_readonly("to", &widgets::Binding::to)
      .def_readonly("mask", &widgets::Binding::mask)
      .def_readonly("rule", &widgets::Binding::rule)
      .def_readonly("oneWay", &widgets::Binding::oneWay);

  py::class_<widgets::CellSpec>(m, "CellSpec", R"doc(Which lattice points a cell groups: made by CellSpec.point/edge/face/slab/box/custom.

Grid indices (i, j, k), flat index i + l*(j + m*k). Fields: kind, base, axis, indices. A spec
outside the lattice's grid is refused by WidgetModel.addCell (WidgetError InvalidArgument).)doc")
      .def_readonly("kind", &widgets::CellSpec::kind)
      .def_readonly("base", &widgets::CellSpec::base)
      .def_readonly("axis", &widgets::CellSpec::axis)
      .def_readonly("indices", &widgets::CellSpec::indices)
      .def_static("point", &widgets::CellSpec::point, "i"_a, "j"_a, "k"_a, R"doc(The point (i, j, k).

Args:
    i, j, k: grid indices.
Returns:
    CellSpec.)doc")
      .def_static("edge", &widgets::CellSpec::edge, "i"_a, "j"_a, "k"_a, "alongAxis"_a, R"doc(The edge from (i, j, k) to the next point along an axis.

Args:
    i, j, k: grid indices of its lower end.
    alongAxis: 0, 1 or 2.
Returns:
    CellSpec.)doc")
      .def_static("face", &widgets::CellSpec::face, "i"_a, "j"_a, "k"_a, "normalAxis"_a, R"doc(The quad with lower corner (i, j, k) in the plane normal to an axis.

Args:
    i, j, k: grid indices of its lower corner.
    normalAxis: 0, 1 or 2.
Returns:
    CellSpec.)doc")
      .def_static("slab", &widgets::CellSpec::slab, "normalAxis"_a, "planeIndex"_a, R"doc(Every point of one plane of the grid.

Args:
    normalAxis: the axis normal to the plane (0, 1 or 2).
    planeIndex: the plane's index along that axis.
Returns:
    CellSpec.)doc")
      .def_static("box", &widgets::CellSpec::box, "i"_a, "j"_a, "k"_a, R"doc(The 2 x 2 x 2 points with lower corner (i, j, k).

Args:
    i, j, k: grid indices of the lower corner.
Returns:
    CellSpec.)doc")
      .def_static("custom", &widgets::CellSpec::custom, "flatIndices"_a, R"doc(Any points, by flat index.

Args:
    flatIndices: at least one, no duplicates.
Returns:
    CellSpec.)doc")
      .def(py::self == py::self);

  py::class_<widgets::Ray>(m, "Ray", R"doc(A world-space ray origin + t * direction, for picking and dragging.

Ray(origin, direction); fields origin, direction; at(t).)doc")
      .def(py::init([](const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) {
             return widgets::Ray{origin, direction};
           }),
           "origin"_a, "direction"_a, R"doc(A ray.

Args:
    origin: 3 numbers, world.
    direction: 3 numbers, non-zero (normalised where used).)doc")
      .def_readwrite("origin", &widgets::Ray::origin)
      .def_readwrite("direction", &widgets::Ray::direction)
      .def("at", &widgets::Ray::at, "t"_a, R"doc(The point at distance t along the (normalised) direction.

Args:
    t: distance from the origin.
Returns:
    3-vector.)doc");
  py::class_<widgets::PickResult>(m, "PickResult", R"doc(What WidgetModel.pick hit.

Fields: id (the widget), t (distance along the ray), point (world hit point).)doc")
      .def_readonly("id", &widgets::PickResult::id)
      .def_readonly("t", &widgets::PickResult::t)
      .def_readonly("point", &widgets::PickResult::point);

  py::class_<widgets::LatticeSettings>(m, "LatticeSettings", R"doc(The FFD settings of a lattice widget: bases and outside policy.

Fields: basis (three ffd.AxisBasis, u v w; Bernstein by default), outside (ffd.OutsidePolicy).
Setting basis to anything but three bases raises ValueError.)doc")
      .def(py::init<>(), R"doc(Default settings: Bernstein bases on every axis, the Identity outside policy.

Edit basis and outside, then pass them to WidgetModel.addLattice or setLatticeSettings.)doc")
      .def_property(
          "basis", [](const widgets::LatticeSettings& s) { return std::vector<ffd::AxisBasis>(s.basis.begin(), s.basis.end()); },
          [](widgets::LatticeSettings& s, const std::vector<ffd::AxisBasis>& bases) {
            if (bases.size() != 3) throw py::value_error("basis: expected three AxisBasis (u, v, w)");
            s.basis = {bases[0], bases[1], bases[2]};
          })
      .def_readwrite("outside", &widgets::LatticeSettings::outside);
}

void bindModel(py::module_& m) {
  py::class_<WidgetModel> modelClass(m, "WidgetModel", R"doc(The headless widget model (widgets/widget_model.h; Kuriyama 1996, ch. 6).

Lattice widgets own their control points; cell widgets group them; affine widgets (translate,
rotate, scale) attached to cells move them; bindings carry one widget's motion to another.
Every failing call raises ffdkit.WidgetError (a ValueError; .code names the kind) and leaves the
model unchanged.)doc");
  modelClass.def(py::init<>(), R"doc(An empty model.

Add lattices with addLattice, then cells, affine widgets and bindings.)doc")
      .def("copy", [](const WidgetModel& model) { return WidgetModel(model); }, R"doc(An independent copy of the model (without an active gesture).

Returns:
    WidgetModel.)doc")
      // building
      .def("addLattice",
           [](WidgetModel& model, const std::string& name, const Eigen::Vector3i& counts, const py::object& frame,
              const py::object& restPoints, const py::object& settings) {
             widgets::LatticeOptions options;
             options.name = name;
             options.counts = counts;
             options.frame = affineArg(frame, "frame");
             if (!restPoints.is_none()) options.restPoints = PointsArg(restPoints, "restPoints").ref();
             if (!settings.is_none()) options.settings = settings.cast<widgets::LatticeSettings>();
             return model.addLattice(options);
           },
           "name"_a = "", "counts"_a = Eigen::Vector3i(2, 2, 2), "frame"_a = py::none(), "restPoints"_a = py::none(),
           "settings"_a = py::none(), R"doc(Adds a root lattice widget.

Args:
    name: unique; "" -> "lattice<N>".
    counts: (l, m, n) control points, each >= 2.
    frame: 4 x 4 world placement (default identity).
    restPoints: l*m*n x 3 local rest points (default the unit box's grid).
    settings: LatticeSettings (default Bernstein bases).
Returns:
    WidgetId.
Raises:
    WidgetError: counts < 2, a bad rest shape or non-finite values, a duplicate name.)doc")
      .def("addCell", &WidgetModel::addCell, "lattice"_a, "spec"_a, "name"_a = "", R"doc(Adds a cell of a lattice.

Args:
    lattice: WidgetId of a lattice.
    spec: CellSpec.
    name: unique; "" -> a generated name.
Returns:
    WidgetId.
Raises:
    WidgetError: an unknown lattice, a spec outside its grid, a duplicate name.)doc")
      .def("addAffine",
           [](WidgetModel& model, WidgetId cell, widgets::AffineKind kind, const std::string& name,
              const py::object& placement) {
             return model.addAffine(cell, kind, name, affineArg(placement, "placement"));
           },
           "cell"_a, "kind"_a, "name"_a = "", "placement"_a = py::none(), R"doc(Adds an affine widget attached to a cell (with its Attachment binding).

Args:
    cell: WidgetId of a cell.
    kind: AffineKind.
    name: unique; "" -> "<kind><N>".
    placement: 4 x 4 relative to the cell's rest frame (default identity).
Returns:
    WidgetId.
Raises:
    WidgetError: an unknown cell, a duplicate name, a kind the cell cannot carry.)doc")
      .def("addFreeAffine",
           [](WidgetModel& model, widgets::AffineKind kind, const std::string& name, const py::object& placement) {
             widgets::AffineOptions options;
             options.name = name;
             options.placement = affineArg(placement, "placement");
             return model.addFreeAffine(kind, options);
           },
           "kind"_a, "name"_a = "", "placement"_a = py::none(), R"doc(Adds an affine widget on no cell (e.g. a press handle); placement is its world frame.

Args:
    kind: AffineKind.
    name: unique; "" -> "<kind><N>".
    placement: 4 x 4 world frame (default identity).
Returns:
    WidgetId.
Raises:
    WidgetError: a duplicate name.)doc")
      .def("bind",
           [](WidgetModel& model, WidgetId a, WidgetId b, const std::optional<widgets::ConversionRule>& rule,
              const std::optional<widgets::AffineMask>& mask, bool oneWay) {
             widgets::BindingOptions options;
             if (rule) options.rule = *rule;
             options.mask = mask;
             options.oneWay = oneWay;
             return model.bind(a, b, options);
           },
           "a"_a, "b"_a, "rule"_a = py::none(), "mask"_a = py::none(), "oneWay"_a = false, R"doc(Binds two widgets; the kind follows from their types (Kuriyama 1996, sec. 6.2.2).

Args:
    a, b: WidgetIds (cell+affine: Attachment; affine+affine: Variation; cell+cell: CellMotion;
        cell+lattice: Hierarchy).
    rule: ConversionRule of a Variation binding (default gain 1).
    mask: AffineMask (default by kind).
    oneWay: only a drives b.
Returns:
    BindingId.
Raises:
    WidgetError: unknown widgets, an unsupported pair or self binding, a duplicate binding, a
        hierarchy cycle, a zero gain, or a loop whose gains do not multiply to 1.)doc")
      .def("unbind", &WidgetModel::unbind, "binding"_a, R"doc(Removes a binding.

Args:
    binding: BindingId.
Raises:
    WidgetError: an unknown binding.)doc")
      .def("remove", &WidgetModel::remove, "id"_a, R"doc(Removes a widget and its bindings.

A lattice takes its cells and their widgets along (child lattices become roots); a cell's
widgets become free.
Args:
    id: WidgetId.
Raises:
    WidgetError: an unknown widget, or during a gesture.)doc")
      .def("rename", &WidgetModel::rename, "id"_a, "name"_a, R"doc(Renames a widget.

Args:
    id: WidgetId.
    name: the new unique, non-empty name.
Raises:
    WidgetError: an unknown widget, an empty or duplicate name.)doc")
      .def("setPlacement",
           [](WidgetModel& model, WidgetId id, const py::object& p) { model.setPlacement(id, affineArg(p, "placement")); },
           "affine"_a, "placement"_a, R"doc(Sets an affine widget's placement (relative to its cell's rest frame; a free widget's world frame).

Args:
    affine: WidgetId.
    placement: 4 x 4 affine matrix.
Raises:
    WidgetError: not an affine widget. ValueError: not a 4 x 4 matrix.)doc")
      .def("setAffineKind", &WidgetModel::setAffineKind, "affine"_a, "kind"_a, R"doc(Changes what an affine widget does; its variation restarts at 0, bindings are kept.

Args:
    affine: WidgetId.
    kind: AffineKind.
Raises:
    WidgetError: not an affine widget.)doc")
      .def("setMask", &WidgetModel::setMask, "binding"_a, "mask"_a, R"doc(Sets the parts a binding carries.

Args:
    binding: BindingId.
    mask: AffineMask.
Raises:
    WidgetError: an unknown binding or a Variation binding.)doc")
      .def("setRule", &WidgetModel::setRule, "binding"_a, "rule"_a, R"doc(Sets a Variation binding's conversion rule.

Args:
    binding: BindingId.
    rule: ConversionRule.
Raises:
    WidgetError: an unknown binding, a zero or non-finite gain, an inconsistent loop.)doc")
      .def("setOneWay", &WidgetModel::setOneWay, "binding"_a, "oneWay"_a, R"doc(Makes a binding one-way (only from_ drives to) or two-way.

Args:
    binding: BindingId.
    oneWay: bool.
Raises:
    WidgetError: an unknown binding.)doc")
      .def("setLatticeSettings", &WidgetModel::setLatticeSettings, "lattice"_a, "settings"_a, R"doc(Sets a lattice's bases and outside policy.

Args:
    lattice: WidgetId.
    settings: LatticeSettings.
Raises:
    WidgetError: not a lattice, or bases its counts cannot carry.)doc")
      .def("setLatticeCounts", &WidgetModel::setLatticeCounts, "lattice"_a, "counts"_a, R"doc(Changes a lattice's point counts, keeping its deformation as well as the new lattice can hold it.

Args:
    lattice: WidgetId.
    counts: (l, m, n), each >= 2.
Raises:
    WidgetError: during a gesture, counts < 2, a basis the new count cannot carry, or a cell that
        no longer fits (the model is then unchanged).)doc")
      .def("setLatticeFrame",
           [](WidgetModel& model, WidgetId id, const py::object& f) { model.setLatticeFrame(id, affineArg(f, "frame")); },
           "lattice"_a, "frame"_a, R"doc(Sets a root lattice's world frame.

Args:
    lattice: WidgetId of a root lattice.
    frame: 4 x 4 affine matrix.
Raises:
    WidgetError: not a lattice, a child lattice, a singular frame.)doc")
      .def("setControlPoints",
           [](WidgetModel& model, WidgetId id, const py::object& points) {
             model.setControlPoints(id, PointsArg(points, "points").ref());
           },
           "lattice"_a, "points"_a, R"doc(Sets every control point of a lattice.

Args:
    lattice: WidgetId.
    points: pointCount x 3, lattice-local.
Raises:
    WidgetError: not a lattice, wrong row count or non-finite values.)doc")
      .def("resetLattice", &WidgetModel::resetLattice, "lattice"_a, R"doc(Puts a lattice back to rest: control points = rest points, its widgets' variations = 0.

Args:
    lattice: WidgetId.
Raises:
    WidgetError: not a lattice.)doc");
  bindWidgetModelQueries(modelClass);
  bindWidgetModelGestures(modelClass);
  modelClass.def("__repr__", [](const WidgetModel& model) {
        return "<ffdkit.widgets.WidgetModel: " + std::to_string(model.widgets(widgets::WidgetType::Lattice).size()) +
               " lattices, " + std::to_string(model.widgets().size()) + " widgets, " +
               std::to_string(model.bindings().size()) + " bindings>";
      });
}

}  // namespace

void bindWidgets(py::module_& module) {
  bindValueTypes(module);
  bindModel(module);
}

}  // namespace ffdkit::python
