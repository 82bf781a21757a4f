// The extension module ffdkit._ffdkit: submodules ffd, widgets and scenes mirroring the C++
// namespaces, and the C++ exceptions as Python exception classes with the same messages.

#include <exception>
#include <string>

#include <pybind11/pybind11.h>

#include "bindings.h"
#include "ffdkit/ffd/cancelled.h"
#include "ffdkit/ffd/closed_surface.h"
#include "ffdkit/ffd/lattice_error.h"
#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/generator.h"
#include "ffdkit/scenes/mesh_io.h"
#include "ffdkit/scenes/scene_file.h"
#include "ffdkit/scenes/widget_file.h"
#include "ffdkit/widgets/widget_error.h"

namespace py = pybind11;
using namespace ffdkit;

namespace {

// Exception classes: created once with PyErr_NewException (which takes several bases, so that
// `except ValueError` still catches bad input) and owned by the module.
struct ErrorClasses {
  PyObject* base = nullptr;
  PyObject* lattice = nullptr;
  PyObject* constraint = nullptr;
  PyObject* cancelled = nullptr;
  PyObject* widget = nullptr;
  PyObject* widgetFile = nullptr;
  PyObject* sceneFile = nullptr;
  PyObject* meshIo = nullptr;
  PyObject* generator = nullptr;
  PyObject* animation = nullptr;
};
ErrorClasses errors;

PyObject* addError(py::module_& module, const char* name, py::tuple bases, const char* doc) {
  const std::string qualified = std::string("ffdkit.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if (!type) throw py::error_already_set();
  module.add_object(name, py::handle(type));  // steals nothing: add_object increments
  return type;
}

}  // namespace

PYBIND11_MODULE(_ffdkit, module) {
  module.doc() = "ffdkit: free-form deformation with 3D widgets (the C++ API; see docs/python.md)";
  module.attr("__version__") = FFDKIT_VERSION;

  py::handle valueError(PyExc_ValueError), runtimeError(PyExc_RuntimeError), osError(PyExc_OSError);
  errors.base = addError(module, "Error", py::make_tuple(py::handle(PyExc_Exception)),
                         R"doc(Base class of every ffdkit error.

Catch it to handle any error of the module; the message names the file, the widget or the
argument concerned.)doc");
  py::handle base(errors.base);
  errors.lattice = addError(module, "LatticeError", py::make_tuple(base, valueError),
                            R"doc(Bad input to the FFD engine (ffd::LatticeError); also a ValueError.

Raised for bad lattice counts, bases, frames or control points, non-finite points, and an
embedding used with a lattice it was not built for ("embedding is stale ... re-embed").)doc");
  errors.constraint = addError(module, "ConstraintError", py::make_tuple(base, valueError),
                               R"doc(A shape constraint that is malformed or cannot be met (ffd::ConstraintError); also a ValueError.

Raised for an open surface where a volume needs a closed one (the message names the edge and
the triangle), sizes that differ, and constraints no allowed control change meets.)doc");
  errors.cancelled = addError(module, "Cancelled", py::make_tuple(base),
                              R"doc(A long computation stopped because its progress callback returned False.

Raised by embed, deformPoints, Deformer.fromPoints, Pipeline.update / reembedAll and
SceneDeformer updates; what was computed before the cancel is kept as the C++ API documents.)doc");
  errors.widget = addError(module, "WidgetError", py::make_tuple(base, valueError),
                           R"doc(A widget model call that cannot be done (widgets::WidgetError); also a ValueError.

.code names the kind: "UnknownWidget", "InvalidArgument", "InvalidBinding", "InconsistentLoop"
or "GestureState"; .where is the location in a widget file's data, or "". The model is unchanged.)doc");
  errors.widgetFile = addError(module, "WidgetFileError", py::make_tuple(base, valueError),
                               R"doc(A widget file that cannot be read or written; also a ValueError.

The message names the file and the JSON pointer of what is wrong.)doc");
  errors.sceneFile = addError(module, "SceneFileError", py::make_tuple(base, valueError),
                              R"doc(A scene file that cannot be read or written; also a ValueError.

The message names the file and the JSON pointer of what is wrong.)doc");
  errors.meshIo = addError(module, "MeshIoError", py::make_tuple(base, osError),
                           R"doc(A mesh or point file that cannot be read or written; also an OSError.

The message names the file and the element or line ("bunny.obj:14: face 3: ...").)doc");
  errors.generator = addError(module, "GeneratorError", py::make_tuple(base, valueError),
                              R"doc(A generator that cannot run with the given parameters; also a ValueError.

The message names the generator and the parameter (unknown names, bad values, failed solves).)doc");
  errors.animation = addError(module, "AnimationError", py::make_tuple(base, valueError),
                              R"doc(A key or animation that cannot be set or evaluated (scenes::AnimationError); also a ValueError.

Raised for a kind a widget cannot key, a value of the wrong shape, a time out of range, or an
animation applied during a gesture.)doc");

  py::register_exception_translator([](std::exception_ptr pointer) {
    if (!pointer) return;
    try {
      std::rethrow_exception(pointer);
    } catch (const ffd::LatticeError& e) {
      PyErr_SetString(errors.lattice, e.what());
    } catch (const ffd::ConstraintError& e) {
      PyErr_SetString(errors.constraint, e.what());
    } catch (const ffd::Cancelled& e) {
      PyErr_SetString(errors.cancelled, e.what());
    } catch (const widgets::WidgetError& e) {
      static const char* const kCodes[] = {"UnknownWidget", "InvalidArgument", "InvalidBinding",
                                           "InconsistentLoop", "GestureState"};
      py::object error = py::reinterpret_borrow<py::object>(errors.widget)(e.what());
      error.attr("code") = kCodes[static_cast<int>(e.code())];
      error.attr("where") = e.where();
      PyErr_SetObject(errors.widget, error.ptr());
    } catch (const scenes::WidgetFileError& e) {
      PyErr_SetString(errors.widgetFile, e.what());
    } catch (const scenes::SceneFileError& e) {
      PyErr_SetString(errors.sceneFile, e.what());
    } catch (const scenes::MeshIoError& e) {
      PyErr_SetString(errors.meshIo, e.what());
    } catch (const scenes::GeneratorError& e) {
      PyErr_SetString(errors.generator, e.what());
    } catch (const scenes::AnimationError& e) {
      PyErr_SetString(errors.animation, e.what());
    }
  });

  py::module_ ffdModule = module.def_submodule("ffd", "The FFD / EFFD engine (C++ namespace ffdkit::ffd).");
  python::bindFfd(ffdModule);
  python::bindLatticeWeights(ffdModule);
  python::bindBoxBernstein(ffdModule);
  python::bindShapeConstraints(ffdModule);
  py::module_ widgetsModule = module.def_submodule("widgets", "The headless widget model (ffdkit::widgets).");
  python::bindWidgets(widgetsModule);
  python::bindWidgetWeights(widgetsModule);
  py::module_ scenesModule =
      module.def_submodule("scenes", "Scenes, widget and scene files, mesh I/O, generators (ffdkit::scenes).");
  python::bindScenes(scenesModule);
  py::module_ appModule =
      module.def_submodule("app", "Scenes edited as the app edits them, with undo (ffdkit::app's controller).");
  python::bindApp(appModule);
  py::module_ ioModule =
      module.def_submodule("_io", "Volume meshes read and written back by pass-through (ffdkit::meshio); see ffdkit.io.");
  python::bindIo(ioModule);
  python::addCadModule(module, base);
}
