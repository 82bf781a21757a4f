// Control-point weights of rational lattices (NURBS-based FFD, Lamousin & Waggenspack 1994) on
// ffdkit.ffd.Lattice and ffdkit.widgets.WidgetModel. Names mirror ffd/lattice.h and
// widgets/widget_model.h; see docs/python.md.

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "ffdkit/ffd/lattice.h"
#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::python {

using namespace pybind11::literals;

void bindLatticeWeights(py::module_& module) {
  auto lattice = py::reinterpret_borrow<py::class_<ffd::Lattice>>(module.attr("Lattice"));
  lattice
      .def_property("weights", &ffd::Lattice::weights,
                    [](ffd::Lattice& l, const Eigen::VectorXd& w) { l.setWeights(w); },
                    R"doc(Current control-point weights, pointCount values > 0 (a copy; assign to change them).

All 1 (the default) is the polynomial lattice; other weights make the map the ratio
sum B w P / sum B w, and a larger weight pulls the shape towards its control point.)doc")
      .def_property("restWeights", &ffd::Lattice::restWeights,
                    [](ffd::Lattice& l, const Eigen::VectorXd& w) { l.setRestWeights(w); },
                    R"doc(Rest weights, the weights of the rest map that embedding inverts (a copy).

Assigning them resets the current weights to them and makes embeddings stale.)doc")
      .def_property_readonly("isRational", &ffd::Lattice::isRational,
                             "True when some current or rest weight is not 1.")
      .def_property_readonly("restIsRational", &ffd::Lattice::restIsRational, "True when some rest weight is not 1.")
      .def("setWeights", [](ffd::Lattice& l, const Eigen::VectorXd& w) { l.setWeights(w); }, "weights"_a,
           R"doc(Sets every current weight.

Args:
    weights: pointCount values, each finite and > 0, in control-point order.
Raises:
    LatticeError: a wrong count or a bad weight (the message names its index).)doc")
      .def("setWeight", &ffd::Lattice::setWeight, "flat"_a, "weight"_a, R"doc(Sets the weight of one control point.

Args:
    flat: the control point's flat index i + l*(j + m*k).
    weight: finite and > 0.
Raises:
    LatticeError: an index out of range or a bad weight.)doc")
      .def("weight", &ffd::Lattice::weight, "flat"_a, R"doc(The weight of one control point.

Args:
    flat: the control point's flat index.
Returns:
    float: its current weight.
Raises:
    LatticeError: an index out of range.)doc")
      .def("setRestWeights", [](ffd::Lattice& l, const Eigen::VectorXd& w) { l.setRestWeights(w); }, "weights"_a,
           R"doc(Sets the rest weights and resets the current weights to them (control points are kept).

Args:
    weights: pointCount values, each finite and > 0.
Raises:
    LatticeError: a wrong count or a bad weight; embeddings built before are stale.)doc");
}

void bindWidgetWeights(py::module_& module) {
  using widgets::WidgetId;
  using widgets::WidgetModel;
  auto model = py::reinterpret_borrow<py::class_<WidgetModel>>(module.attr("WidgetModel"));
  model
      .def("weights", &WidgetModel::weights, "lattice"_a, R"doc(The control-point weights of a lattice.

Args:
    lattice: WidgetId of a lattice.
Returns:
    numpy.ndarray: pointCount weights (all 1 for a polynomial lattice).
Raises:
    WidgetError: not a lattice.)doc")
      .def("isRational", &WidgetModel::isRational, "lattice"_a, R"doc(Whether some weight of a lattice is not 1.

Args:
    lattice: WidgetId of a lattice.
Returns:
    bool: True for a rational lattice.
Raises:
    WidgetError: not a lattice.)doc")
      .def("setWeights", [](WidgetModel& m, WidgetId id, const Eigen::VectorXd& w) { m.setWeights(id, w); }, "lattice"_a,
           "weights"_a, R"doc(Sets every control-point weight of a lattice (an undoable control edit).

Args:
    lattice: WidgetId of a lattice.
    weights: pointCount values, each finite and > 0 (all 1: polynomial again).
Raises:
    WidgetError: during a gesture, not a lattice, a wrong count or a bad weight.)doc")
      .def("setWeight", &WidgetModel::setWeight, "lattice"_a, "point"_a, "weight"_a,
           R"doc(Sets the weight of one control point of a lattice.

Args:
    lattice: WidgetId of a lattice.
    point: the control point's flat index.
    weight: finite and > 0.
Raises:
    WidgetError: during a gesture, not a lattice, an index out of range or a bad weight.)doc");
}

}  // namespace ffdkit::python
