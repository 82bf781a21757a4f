// ffdkit.widgets.WidgetModel, continued: gestures, picks and drags by rays, and whole motions
// (Kuriyama 1996, ch. 6). Names mirror widgets/widget_model.h; see docs/python.md.

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

void bindWidgetModelGestures(py::class_<WidgetModel>& modelClass) {
  modelClass
      .def("beginGesture", &WidgetModel::beginGesture, "id"_a, R"doc(Starts a gesture on a widget: the start state and the order of the bindings to visit are recorded.

Args:
    id: WidgetId.
Raises:
    WidgetError: a gesture is active (GestureState), or an unknown widget.)doc")
      .def("updateGesture",
           [](WidgetModel& model, const py::object& change) {
             if (py::isinstance<py::float_>(change) || py::isinstance<py::int_>(change)) {
               model.updateGesture(change.cast<double>());
             } else {
               model.updateGesture(affineArg(change, "worldMotion"));
             }
           },
           "change"_a, R"doc(Moves the gesture's widget; bindings follow, from the start state (no drift).

Args:
    change: a number (affine widget: the variation change since the start) or a 4 x 4 matrix
        (cell or lattice: its world motion since the start).
Raises:
    WidgetError: no gesture is active (GestureState). ValueError: a matrix that is not 4 x 4.)doc")
      .def("endGesture", &WidgetModel::endGesture, R"doc(Ends the gesture; its changes stay.

Raises:
    WidgetError: no gesture is active (GestureState).)doc")
      .def("cancelGesture", &WidgetModel::cancelGesture, R"doc(Ends the gesture and restores the state at its start.

Raises:
    WidgetError: no gesture is active (GestureState).)doc")
      .def("gestureActive", &WidgetModel::gestureActive, R"doc(True between beginGesture() and endGesture() / cancelGesture().

Returns:
    bool.)doc")
      .def("gestureWidget", &WidgetModel::gestureWidget, R"doc(The widget of the active gesture.

Returns:
    WidgetId, or None when no gesture is active.)doc")
      .def("gestureVisitOrder", &WidgetModel::gestureVisitOrder, R"doc(The widgets the active gesture moves, in visiting order (for highlighting).

Returns:
    list of WidgetId (empty when no gesture is active).)doc")
      .def("pick",
           [](const WidgetModel& model, const widgets::Ray& ray, double tolerance, bool affines, bool cells,
              bool lattices) {
             return model.pick(ray, widgets::PickOptions{tolerance, affines, cells, lattices});
           },
           "ray"_a, "tolerance"_a = 0.02, "affines"_a = true, "cells"_a = true, "lattices"_a = false, R"doc(The nearest widget a ray hits: glyphs of affine widgets, cells' points, edges and faces.

Args:
    ray: Ray in the world.
    tolerance: how far from a thin glyph the ray may pass (world units).
    affines, cells, lattices: which kinds to consider (lattices: their bounding boxes).
Returns:
    PickResult, or None on a miss.)doc")
      .def("beginDrag", &WidgetModel::beginDrag, "id"_a, "ray"_a, R"doc(Begins a drag of a widget grabbed by a ray (a gesture driven by rays).

Args:
    id: WidgetId.
    ray: the ray through the grab point.
Raises:
    WidgetError: a gesture is active, or an unknown widget.)doc")
      .def("dragTo", &WidgetModel::dragTo, "ray"_a, R"doc(Moves the active drag to a new mouse ray (rays parallel to the drag line keep the last value).

Args:
    ray: Ray.
Raises:
    WidgetError: no drag is active (GestureState).)doc")
      .def("applyVariation", &WidgetModel::applyVariation, "affine"_a, "delta"_a, R"doc(Changes an affine widget's variation by delta, as one whole gesture (bindings follow).

Args:
    affine: WidgetId.
    delta: a distance, an angle (rad) or a log scale factor.
Raises:
    WidgetError: not an affine widget, or a gesture is active.)doc")
      .def("setVariation", &WidgetModel::setVariation, "affine"_a, "value"_a, R"doc(Sets an affine widget's variation to value, as one whole gesture (bindings follow).

Args:
    affine: WidgetId.
    value: the new variation.
Raises:
    WidgetError: not an affine widget, or a gesture is active.)doc")
      .def("applyMotion",
           [](WidgetModel& model, WidgetId id, const py::object& motion) {
             model.applyMotion(id, affineArg(motion, "worldMotion"));
           },
           "id"_a, "worldMotion"_a, R"doc(Moves a cell or lattice by a world motion, as one whole gesture (bindings follow).

Args:
    id: WidgetId of a cell or lattice.
    worldMotion: 4 x 4 affine matrix.
Raises:
    WidgetError: not a cell or lattice, or a gesture is active.)doc");
}

}  // namespace ffdkit::python
