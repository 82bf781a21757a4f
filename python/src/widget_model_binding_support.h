// The parts of ffdkit.widgets.WidgetModel bound outside widgets_bindings.cpp, which makes the class
// and calls them in order.
#pragma once

#include <pybind11/pybind11.h>

#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::python {

namespace py = pybind11;

/// WidgetModel's queries: widgets and names, bindings, lattices and their points, cells, affine
/// widgets (widget_model_query_bindings.cpp).
void bindWidgetModelQueries(py::class_<widgets::WidgetModel>& modelClass);

/// WidgetModel's gestures, picks, drags and whole motions (widget_model_gesture_bindings.cpp).
void bindWidgetModelGestures(py::class_<widgets::WidgetModel>& modelClass);

}  // namespace ffdkit::python
