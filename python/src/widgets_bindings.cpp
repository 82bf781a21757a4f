// ffdkit.widgets: the headless widget model of Kuriyama 1996, ch. 6
// (widgets/include/ffdkit/widgets). Names mirror the C++ API; lattice points come back as numpy
// arrays (N x 3).

#include <string>
#include <utility>

#include <pybind11/eigen.h>
#include <pybind11/operators.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "ffdkit/widgets/widget_model.h"
#include "numpy_eigen.h"

namespace ffdkit::python {

using namespace pybind11::literals;
using widgets::WidgetId;
using widgets::WidgetModel;

namespace {

void bindValueTypes(py::module_& m) {
  py::class_<WidgetId>(m, "WidgetId", "Handle of a widget in one model; printed as w<N>.")
      .def_readonly("value", &WidgetId::value)
      .def("valid", &WidgetId::valid)
      .def(py::self == py::self)
      .def(py::self < py::self)
      .def("__hash__", [](const WidgetId& id) { return std::hash<std::uint32_t>{}(id.value); })
      .def("__repr__", [](const WidgetId& id) { return widgets::toString(id); });
  py::class_<widgets::BindingId>(m, "BindingId")
      .def_readonly("value", &widgets::BindingId::value)
      .def(py::self == py::self)
      .def("__hash__", [](const widgets::BindingId& id) { return std::hash<std::uint32_t>{}(id.value); })
      .def("__repr__", [](const widgets::BindingId& id) { return widgets::toString(id); });

  py::enum_<widgets::WidgetType>(m, "WidgetType")
      .value("Lattice", widgets::WidgetType::Lattice)
      .value("Cell", widgets::WidgetType::Cell)
      .value("Affine", widgets::WidgetType::Affine);
  py::enum_<widgets::AffineKind>(m, "AffineKind")
      .value("Translate", widgets::AffineKind::Translate)
      .value("Rotate", widgets::AffineKind::Rotate)
      .value("Scale", widgets::AffineKind::Scale);
  py::enum_<widgets::CellKind>(m, "CellKind")
      .value("Point", widgets::CellKind::Point)
      .value("Edge", widgets::CellKind::Edge)
      .value("Face", widgets::CellKind::Face)
      .value("Slab", widgets::CellKind::Slab)
      .value("Box", widgets::CellKind::Box)
      .value("Custom", widgets::CellKind::Custom);
  py::enum_<widgets::BindingKind>(m, "BindingKind")
      .value("Attachment", widgets::BindingKind::Attachment)
      .value("Variation", widgets::BindingKind::Variation)
      .value("CellMotion", widgets::BindingKind::CellMotion)
      .value("Hierarchy", widgets::BindingKind::Hierarchy);

  py::class_<widgets::AffineMask>(m, "AffineMask", "Which of translation, rotation, scale a binding carries.")
      .def(py::init([](bool t, bool r, bool s) { return widgets::AffineMask{t, r, s}; }), "translate"_a = true,
           "rotate"_a = true, "scale"_a = false)
      .def_readwrite("translate", &widgets::AffineMask::translate)
      .def_readwrite("rotate", &widgets::AffineMask::rotate)
      .def_readwrite("scale", &widgets::AffineMask::scale)
      .def_static("parse", [](const std::string& text) {
        auto mask = widgets::parseMask(text);
        if (!mask) throw py::value_error("mask: expected letters T, R, S at most once each, got '" + text + "'");
        return *mask;
      }, "text"_a)
      .def(py::self == py::self)
      .def("__str__", &widgets::maskString)
      .def("__repr__", [](const widgets::AffineMask& mask) { return "AffineMask('" + widgets::maskString(mask) + "')"; });

  py::class_<widgets::VariationRange>(m, "VariationRange")
      .def(py::init([](double lo, double hi) { return widgets::VariationRange{lo, hi}; }), "min"_a, "max"_a)
      .def_readwrite("min", &widgets::VariationRange::min)
      .def_readwrite("max", &widgets::VariationRange::max);
  py::class_<widgets::ConversionRule>(m, "ConversionRule", "delta_to = gain * delta_from, optionally clamped.")
      .def(py::init<double, std::optional<widgets::VariationRange>>(), "gain"_a = 1.0, "clamp"_a = py::none())
      .def_readwrite("gain", &widgets::ConversionRule::gain)
      .def_readwrite("clamp", &widgets::ConversionRule::clamp)
      .def_static("screw", &widgets::ConversionRule::screw, "distancePerTurn"_a)
      .def(py::self == py::self);

  py::class_<widgets::Binding>(m, "Binding")
      .def_readonly("id", &widgets::Binding::id)
      .def_readonly("kind", &widgets::Binding::kind)
      .def_readonly("from_", &widgets::Binding::from)
      .def_readonly("to", &widgets::Binding::to)
      .def_readonly("mask", &widgets::Binding::mask)
      .def_readonly("rule", &widgets::Binding::rule)
      .def_readonly("oneWay", &widgets::Binding::oneWay);

  py::class_<widgets::CellSpec>(m, "CellSpec", "Which lattice points a cell groups.")
      .def_readonly("kind", &widgets::CellSpec::kind)
      .def_readonly("base", &widgets::CellSpec::base)
      .def_readonly("axis", &widgets::CellSpec::axis)
      .def_readonly("indices", &widgets::CellSpec::indices)
      .def_static("point", &widgets::CellSpec::point, "i"_a, "j"_a, "k"_a)
      .def_static("edge", &widgets::CellSpec::edge, "i"_a, "j"_a, "k"_a, "alongAxis"_a)
      .def_static("face", &widgets::CellSpec::face, "i"_a, "j"_a, "k"_a, "normalAxis"_a)
      .def_static("slab", &widgets::CellSpec::slab, "normalAxis"_a, "planeIndex"_a)
      .def_static("box", &widgets::CellSpec::box, "i"_a, "j"_a, "k"_a)
      .def_static("custom", &widgets::CellSpec::custom, "flatIndices"_a)
      .def(py::self == py::self);

  py::class_<widgets::Ray>(m, "Ray", "A world-space ray origin + t * direction.")
      .def(py::init([](const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) {
             return widgets::Ray{origin, direction};
           }),
           "origin"_a, "direction"_a)
      .def_readwrite("origin", &widgets::Ray::origin)
      .def_readwrite("direction", &widgets::Ray::direction)
      .def("at", &widgets::Ray::at, "t"_a);
  py::class_<widgets::PickResult>(m, "PickResult")
      .def_readonly("id", &widgets::PickResult::id)
      .def_readonly("t", &widgets::PickResult::t)
      .def_readonly("point", &widgets::PickResult::point);

  py::class_<widgets::LatticeSettings>(m, "LatticeSettings", "Bases, outside policy and cylinder of a lattice widget.")
      .def(py::init<>())
      .def_property(
          "basis", [](const widgets::LatticeSettings& s) { return std::vector<ffd::AxisBasis>(s.basis.begin(), s.basis.end()); },
          [](widgets::LatticeSettings& s, const std::vector<ffd::AxisBasis>& bases) {
            if (bases.size() != 3) throw py::value_error("basis: expected three AxisBasis (u, v, w)");
            s.basis = {bases[0], bases[1], bases[2]};
          })
      .def_readwrite("outside", &widgets::LatticeSettings::outside);
}

py::array latticeView(py::object self, const Eigen::MatrixX3d& points) { return viewOf(points, self, false); }

void bindModel(py::module_& m) {
  py::class_<WidgetModel>(m, "WidgetModel",
                          "Lattice, cell and affine widgets, bindings and gestures (widgets/widget_model.h). "
                          "Errors raise ffdkit.WidgetError and leave the model unchanged.")
      .def(py::init<>())
      .def("copy", [](const WidgetModel& model) { return WidgetModel(model); })
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
           "settings"_a = py::none(), "A root lattice widget (LatticeOptions as keywords).")
      .def("addCell", &WidgetModel::addCell, "lattice"_a, "spec"_a, "name"_a = "")
      .def("addAffine",
           [](WidgetModel& model, WidgetId cell, widgets::AffineKind kind, const std::string& name,
              const py::object& placement) {
             return model.addAffine(cell, kind, name, affineArg(placement, "placement"));
           },
           "cell"_a, "kind"_a, "name"_a = "", "placement"_a = py::none())
      .def("addFreeAffine",
           [](WidgetModel& model, widgets::AffineKind kind, const std::string& name, const py::object& placement) {
             widgets::AffineOptions options;
             options.name = name;
             options.placement = affineArg(placement, "placement");
             return model.addFreeAffine(kind, options);
           },
           "kind"_a, "name"_a = "", "placement"_a = py::none())
      .def("bind",
           [](WidgetModel& model, WidgetId a, WidgetId b, const std::optional<widgets::ConversionRule>& rule,
              const std::optional<widgets::AffineMask>& mask, bool oneWay) {
             widgets::BindingOptions options;
             if (rule) options.rule = *rule;
             options.mask = mask;
             options.oneWay = oneWay;
             return model.bind(a, b, options);
           },
           "a"_a, "b"_a, "rule"_a = py::none(), "mask"_a = py::none(), "oneWay"_a = false,
           "Binds two widgets; the kind follows from their types (Kuriyama 1996, sec. 6.2.2).")
      .def("unbind", &WidgetModel::unbind, "binding"_a)
      .def("remove", &WidgetModel::remove, "id"_a)
      .def("rename", &WidgetModel::rename, "id"_a, "name"_a)
      .def("setPlacement",
           [](WidgetModel& model, WidgetId id, const py::object& p) { model.setPlacement(id, affineArg(p, "placement")); },
           "affine"_a, "placement"_a)
      .def("setAffineKind", &WidgetModel::setAffineKind, "affine"_a, "kind"_a)
      .def("setMask", &WidgetModel::setMask, "binding"_a, "mask"_a)
      .def("setRule", &WidgetModel::setRule, "binding"_a, "rule"_a)
      .def("setOneWay", &WidgetModel::setOneWay, "binding"_a, "oneWay"_a)
      .def("setLatticeSettings", &WidgetModel::setLatticeSettings, "lattice"_a, "settings"_a)
      .def("setLatticeCounts", &WidgetModel::setLatticeCounts, "lattice"_a, "counts"_a)
      .def("setLatticeFrame",
           [](WidgetModel& model, WidgetId id, const py::object& f) { model.setLatticeFrame(id, affineArg(f, "frame")); },
           "lattice"_a, "frame"_a)
      .def("setControlPoints",
           [](WidgetModel& model, WidgetId id, const py::object& points) {
             model.setControlPoints(id, PointsArg(points, "points").ref());
           },
           "lattice"_a, "points"_a)
      .def("resetLattice", &WidgetModel::resetLattice, "lattice"_a)
      // queries
      .def("contains", &WidgetModel::contains, "id"_a)
      .def("type", &WidgetModel::type, "id"_a)
      .def("name", &WidgetModel::name, "id"_a)
      .def("find", &WidgetModel::find, "name"_a)
      .def("widgets", [](const WidgetModel& model, std::optional<widgets::WidgetType> type) {
        return type ? model.widgets(*type) : model.widgets();
      }, "type"_a = py::none())
      .def("names", [](const WidgetModel& model, std::optional<widgets::WidgetType> type) {
        std::vector<std::string> names;
        for (const WidgetId id : type ? model.widgets(*type) : model.widgets()) names.push_back(model.name(id));
        return names;
      }, "type"_a = py::none(), "Widget names in id order (of one type if given).")
      .def("bindings", &WidgetModel::bindings)
      .def("bindingsOf", &WidgetModel::bindingsOf, "id"_a)
      .def("binding", &WidgetModel::binding, "binding"_a)
      .def_property_readonly("revision", &WidgetModel::revision)
      .def("counts", &WidgetModel::counts, "lattice"_a)
      .def("controlPoints",
           [](py::object self, WidgetId id) { return latticeView(self, self.cast<const WidgetModel&>().controlPoints(id)); },
           "lattice"_a, "Local control points (read-only view; the next edit of the model may invalidate it: copy to keep).")
      .def("restPoints",
           [](py::object self, WidgetId id) { return latticeView(self, self.cast<const WidgetModel&>().restPoints(id)); },
           "lattice"_a)
      .def("worldControlPoints", [](const WidgetModel& model, WidgetId id) { return toArray(model.worldControlPoints(id)); },
           "lattice"_a)
      .def("worldRestPoints", [](const WidgetModel& model, WidgetId id) { return toArray(model.worldRestPoints(id)); },
           "lattice"_a)
      .def("latticeFrame", [](const WidgetModel& model, WidgetId id) { return affineToArray(model.latticeFrame(id)); },
           "lattice"_a)
      .def("latticeSettings", &WidgetModel::latticeSettings, "lattice"_a)
      .def("ffdLattice", &WidgetModel::ffdLattice, "lattice"_a, "The FFD engine's lattice of a lattice widget (a copy).")
      .def("parentCell", &WidgetModel::parentCell, "lattice"_a)
      .def("parentLattice", &WidgetModel::parentLattice, "lattice"_a)
      .def("children", &WidgetModel::children, "lattice"_a)
      .def("roots", &WidgetModel::roots)
      .def("pipelineOrder",
           [](const WidgetModel& model, std::optional<WidgetId> root) {
             return root ? model.pipelineOrder(*root) : model.pipelineOrder();
           },
           "root"_a = py::none(), "Lattices in pre-order (of one root's tree if given).")
      .def("cellsOf", &WidgetModel::cellsOf, "lattice"_a)
      .def("latticeOf", &WidgetModel::latticeOf, "id"_a)
      .def("cellSpec", &WidgetModel::cellSpec, "cell"_a)
      .def("cellIndices", &WidgetModel::cellIndices, "cell"_a)
      .def("cellWorldPoints", [](const WidgetModel& model, WidgetId id) { return toArray(model.cellWorldPoints(id)); },
           "cell"_a)
      .def("affinesOf", &WidgetModel::affinesOf, "cell"_a)
      .def("affineKind", &WidgetModel::affineKind, "affine"_a)
      .def("attachedCell", &WidgetModel::attachedCell, "affine"_a)
      .def("placement", [](const WidgetModel& model, WidgetId id) { return affineToArray(model.placement(id)); },
           "affine"_a)
      .def("variation", &WidgetModel::variation, "affine"_a)
      .def("affineFrame",
           [](const WidgetModel& model, WidgetId id) {
             const widgets::WidgetFrame frame = model.affineFrame(id);
             return py::make_tuple(affineToArray(Eigen::Affine3d(frame.frame.matrix())), frame.size);
           },
           "affine"_a, "(4 x 4 rigid world frame, glyph size)")
      // gestures
      .def("beginGesture", &WidgetModel::beginGesture, "id"_a)
      .def("updateGesture",
           [](WidgetModel& model, const py::object& change) {
             if (py::isinstance<py::float_>(change) || py::isinstance<py::int_>(change)) {
               model.updateGesture(change.cast<double>());
             } else {
               model.updateGesture(affineArg(change, "worldMotion"));
             }
           },
           "change"_a,
           "A number: the variation change since the gesture start (affine widget); a 4 x 4 matrix: the world "
           "motion since the start (cell or lattice widget).")
      .def("endGesture", &WidgetModel::endGesture)
      .def("cancelGesture", &WidgetModel::cancelGesture)
      .def("gestureActive", &WidgetModel::gestureActive)
      .def("gestureWidget", &WidgetModel::gestureWidget)
      .def("gestureVisitOrder", &WidgetModel::gestureVisitOrder)
      .def("pick",
           [](const WidgetModel& model, const widgets::Ray& ray, double tolerance, bool affines, bool cells,
              bool lattices) {
             return model.pick(ray, widgets::PickOptions{tolerance, affines, cells, lattices});
           },
           "ray"_a, "tolerance"_a = 0.02, "affines"_a = true, "cells"_a = true, "lattices"_a = false)
      .def("beginDrag", &WidgetModel::beginDrag, "id"_a, "ray"_a)
      .def("dragTo", &WidgetModel::dragTo, "ray"_a)
      .def("applyVariation", &WidgetModel::applyVariation, "affine"_a, "delta"_a)
      .def("setVariation", &WidgetModel::setVariation, "affine"_a, "value"_a)
      .def("applyMotion",
           [](WidgetModel& model, WidgetId id, const py::object& motion) {
             model.applyMotion(id, affineArg(motion, "worldMotion"));
           },
           "id"_a, "worldMotion"_a)
      .def("__repr__", [](const WidgetModel& model) {
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
