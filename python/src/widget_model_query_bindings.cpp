// ffdkit.widgets.WidgetModel, continued: its queries (widgets, names, bindings, lattices and their
// points, cells, affine widgets). Names mirror widgets/widget_model.h; see docs/python.md.

#include <optional>
#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "ffdkit/widgets/widget_model.h"
#include "numpy_eigen.h"
#include "widget_model_binding_support.h"

namespace ffdkit::python {

using namespace pybind11::literals;
using widgets::WidgetId;
using widgets::WidgetModel;

namespace {

py::array latticeView(py::object self, const Eigen::MatrixX3d& points) { return viewOf(points, self, false); }

}  // namespace

void bindWidgetModelQueries(py::class_<WidgetModel>& modelClass) {
  modelClass
      .def("contains", &WidgetModel::contains, "id"_a, R"doc(True when the model holds the widget.

Args:
    id: WidgetId.)doc")
      .def("type", &WidgetModel::type, "id"_a, R"doc(The widget's type.

Args:
    id: WidgetId.
Returns:
    WidgetType.
Raises:
    WidgetError: an unknown widget.)doc")
      .def("name", &WidgetModel::name, "id"_a, R"doc(The widget's name.

Args:
    id: WidgetId.
Raises:
    WidgetError: an unknown widget.)doc")
      .def("find", &WidgetModel::find, "name"_a, R"doc(The widget of that name.

Args:
    name: its name.
Returns:
    WidgetId.
Raises:
    WidgetError: no such widget (the message lists the known names).)doc")
      .def("widgets", [](const WidgetModel& model, std::optional<widgets::WidgetType> type) {
        return type ? model.widgets(*type) : model.widgets();
      }, "type"_a = py::none(), R"doc(The widgets in id order.

Args:
    type: a WidgetType to keep only that type, or None for all.
Returns:
    list of WidgetId.)doc")
      .def("names", [](const WidgetModel& model, std::optional<widgets::WidgetType> type) {
        std::vector<std::string> names;
        for (const WidgetId id : type ? model.widgets(*type) : model.widgets()) names.push_back(model.name(id));
        return names;
      }, "type"_a = py::none(), R"doc(The widgets' names in id order.

Args:
    type: a WidgetType to keep only that type, or None for all.
Returns:
    list of str.)doc")
      .def("bindings", &WidgetModel::bindings, R"doc(Every binding, in id order.

Returns:
    list of BindingId.)doc")
      .def("bindingsOf", &WidgetModel::bindingsOf, "id"_a, R"doc(The bindings with the widget at either end, in id order.

Args:
    id: WidgetId.
Raises:
    WidgetError: an unknown widget.)doc")
      .def("binding", &WidgetModel::binding, "binding"_a, R"doc(A binding's data.

Args:
    binding: BindingId.
Returns:
    Binding.
Raises:
    WidgetError: an unknown binding.)doc")
      .def_property_readonly("revision", &WidgetModel::revision)
      .def("counts", &WidgetModel::counts, "lattice"_a, R"doc(A lattice's control points per axis.

Args:
    lattice: WidgetId.
Returns:
    (l, m, n).
Raises:
    WidgetError: not a lattice.)doc")
      .def("controlPoints",
           [](py::object self, WidgetId id) { return latticeView(self, self.cast<const WidgetModel&>().controlPoints(id)); },
           "lattice"_a, R"doc(A lattice's control points, lattice-local, pointCount x 3.

Args:
    lattice: WidgetId.
Returns:
    A read-only view; the next edit of the model may change it (.copy() to keep).
Raises:
    WidgetError: not a lattice.)doc")
      .def("restPoints",
           [](py::object self, WidgetId id) { return latticeView(self, self.cast<const WidgetModel&>().restPoints(id)); },
           "lattice"_a, R"doc(A lattice's rest points, lattice-local, pointCount x 3.

Args:
    lattice: WidgetId.
Returns:
    A read-only view.
Raises:
    WidgetError: not a lattice.)doc")
      .def("worldControlPoints", [](const WidgetModel& model, WidgetId id) { return toArray(model.worldControlPoints(id)); },
           "lattice"_a, R"doc(A lattice's control points in the world, pointCount x 3.

Args:
    lattice: WidgetId.
Returns:
    A new array.
Raises:
    WidgetError: not a lattice.)doc")
      .def("worldRestPoints", [](const WidgetModel& model, WidgetId id) { return toArray(model.worldRestPoints(id)); },
           "lattice"_a, R"doc(A lattice's rest points at its current frame, in the world, pointCount x 3.

Args:
    lattice: WidgetId.
Raises:
    WidgetError: not a lattice.)doc")
      .def("latticeFrame", [](const WidgetModel& model, WidgetId id) { return affineToArray(model.latticeFrame(id)); },
           "lattice"_a, R"doc(A lattice's world frame (world = frame @ local).

Args:
    lattice: WidgetId.
Returns:
    4 x 4 array (a child lattice: its parent cell's frame times its placement).
Raises:
    WidgetError: not a lattice.)doc")
      .def("latticeSettings", &WidgetModel::latticeSettings, "lattice"_a, R"doc(A lattice's bases and outside policy.

Args:
    lattice: WidgetId.
Returns:
    LatticeSettings.
Raises:
    WidgetError: not a lattice.)doc")
      .def("ffdLattice", &WidgetModel::ffdLattice, "lattice"_a, R"doc(The FFD engine's lattice of a lattice widget, as the deformer uses it (a copy).

Args:
    lattice: WidgetId.
Returns:
    ffd.Lattice with its counts, bases, policy, rest and control points and world frame.
Raises:
    WidgetError: not a lattice.)doc")
      .def("parentCell", &WidgetModel::parentCell, "lattice"_a, R"doc(The cell a child lattice rides on.

Args:
    lattice: WidgetId.
Returns:
    WidgetId, or None for a root.
Raises:
    WidgetError: not a lattice.)doc")
      .def("parentLattice", &WidgetModel::parentLattice, "lattice"_a, R"doc(The lattice of parentCell().

Args:
    lattice: WidgetId.
Returns:
    WidgetId, or None for a root.
Raises:
    WidgetError: not a lattice.)doc")
      .def("children", &WidgetModel::children, "lattice"_a, R"doc(A lattice's child lattices, in sibling order.

Args:
    lattice: WidgetId.
Raises:
    WidgetError: not a lattice.)doc")
      .def("roots", &WidgetModel::roots, R"doc(The root lattices, in sibling order.

Returns:
    list of WidgetId.)doc")
      .def("pipelineOrder",
           [](const WidgetModel& model, std::optional<WidgetId> root) {
             return root ? model.pipelineOrder(*root) : model.pipelineOrder();
           },
           "root"_a = py::none(), R"doc(The lattices in pre-order: the order in which they deform (Kuriyama 1996, secs. 6.2.3, 6.3.2).

Args:
    root: a root lattice to list only its tree, or None for every tree.
Raises:
    WidgetError: root is not a lattice.)doc")
      .def("cellsOf", &WidgetModel::cellsOf, "lattice"_a, R"doc(A lattice's cells, in id order.

Args:
    lattice: WidgetId.
Raises:
    WidgetError: not a lattice.)doc")
      .def("latticeOf", &WidgetModel::latticeOf, "id"_a, R"doc(The lattice of a cell or of an attached affine widget.

Args:
    id: WidgetId.
Returns:
    WidgetId (invalid for a free affine widget).
Raises:
    WidgetError: an unknown widget.)doc")
      .def("cellSpec", &WidgetModel::cellSpec, "cell"_a, R"doc(Which points a cell groups, as given.

Args:
    cell: WidgetId.
Returns:
    CellSpec.
Raises:
    WidgetError: not a cell.)doc")
      .def("cellIndices", &WidgetModel::cellIndices, "cell"_a, R"doc(The flat indices of a cell's points.

Args:
    cell: WidgetId.
Returns:
    list of int.
Raises:
    WidgetError: not a cell.)doc")
      .def("cellWorldPoints", [](const WidgetModel& model, WidgetId id) { return toArray(model.cellWorldPoints(id)); },
           "cell"_a, R"doc(A cell's points in the world, #points x 3.

Args:
    cell: WidgetId.
Raises:
    WidgetError: not a cell.)doc")
      .def("affinesOf", &WidgetModel::affinesOf, "cell"_a, R"doc(The affine widgets attached to a cell, in id order.

Args:
    cell: WidgetId.
Raises:
    WidgetError: not a cell.)doc")
      .def("affineKind", &WidgetModel::affineKind, "affine"_a, R"doc(What an affine widget does.

Args:
    affine: WidgetId.
Returns:
    AffineKind.
Raises:
    WidgetError: not an affine widget.)doc")
      .def("attachedCell", &WidgetModel::attachedCell, "affine"_a, R"doc(The cell an affine widget is attached to.

Args:
    affine: WidgetId.
Returns:
    WidgetId, or None for a free widget.
Raises:
    WidgetError: not an affine widget.)doc")
      .def("placement", [](const WidgetModel& model, WidgetId id) { return affineToArray(model.placement(id)); },
           "affine"_a, R"doc(An affine widget's placement: relative to its cell's rest frame, or its world frame if free.

Args:
    affine: WidgetId.
Returns:
    4 x 4 array.
Raises:
    WidgetError: not an affine widget.)doc")
      .def("variation", &WidgetModel::variation, "affine"_a, R"doc(An affine widget's accumulated variation: a distance, an angle (rad) or a log scale factor.

Args:
    affine: WidgetId.
Raises:
    WidgetError: not an affine widget.)doc")
      .def("affineFrame",
           [](const WidgetModel& model, WidgetId id) {
             const widgets::WidgetFrame frame = model.affineFrame(id);
             return py::make_tuple(affineToArray(Eigen::Affine3d(frame.frame.matrix())), frame.size);
           },
           "affine"_a, R"doc(An affine widget's rigid world frame and glyph size (Kuriyama 1996, sec. 6.2.1).

Args:
    affine: WidgetId.
Returns:
    (4 x 4 frame, size).
Raises:
    WidgetError: not an affine widget.)doc");
}

}  // namespace ffdkit::python
