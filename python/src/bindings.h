#pragma once

#include <pybind11/pybind11.h>

namespace ffdkit::python {

namespace py = pybind11;

/// One function per C++ module, each filling the Python submodule of the same name.
void bindFfd(py::module_& module);
/// ffdkit.ffd's pipelines and direct manipulation (ffd_pipeline_bindings.cpp), called by bindFfd.
void bindFfdPipeline(py::module_& module);
/// ffdkit.ffd.boxBernsteinDeform and its lattice and options (box_bernstein_bindings.cpp).
void bindBoxBernstein(py::module_& module);
/// ffdkit.ffd.ShapeConstraints, enclosedVolume, checkFolding (shape_constraints_bindings.cpp).
void bindShapeConstraints(py::module_& module);
/// Control-point weights on ffdkit.ffd.Lattice (weights_bindings.cpp), after bindFfd.
void bindLatticeWeights(py::module_& module);
void bindWidgets(py::module_& module);
/// Control-point weights on ffdkit.widgets.WidgetModel (weights_bindings.cpp), after bindWidgets.
void bindWidgetWeights(py::module_& module);
void bindScenes(py::module_& module);
/// Parts of ffdkit.scenes bound in animation_bindings.cpp, called by bindScenes: the keyframe
/// enums (before Scene), then Scene's object, lattice and animation editing (after Scene).
void bindAnimationTypes(py::module_& module);
void bindSceneEditing(py::module_& module);
/// ffdkit.app: the Document (scene, deformer, undo stack, interaction controller).
void bindApp(py::module_& module);
/// ffdkit.cad's C++ half, the submodule _cad of `module` (cad_bindings.cpp, with the cad module);
/// CadError derives from `baseError` (ffdkit.Error) and RuntimeError. Without the cad module
/// (FFDKIT_WITH_CAD off: cad_unavailable.cpp) it adds nothing, and importing ffdkit.cad raises
/// ImportError saying so.
void addCadModule(py::module_& module, const py::handle& baseError);
/// ffdkit.io's C++ half: volume meshes read and written back by pass-through (io_bindings.cpp).
void bindIo(py::module_& module);

}  // namespace ffdkit::python
