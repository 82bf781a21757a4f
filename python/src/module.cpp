// The extension module ffdkit._ffdkit: submodules ffd, widgets and scenes mirroring the C++
// namespaces, and the C++ exceptions as Python exception classes with the same messages.

#include <exception>
#include <string>

#include <pybind11/pybind11.h>

#include "bindings.h"
#include "ffdkit/ffd/cancelled.h"
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
                         "Base class of every ffdkit error.");
  py::handle base(errors.base);
  errors.lattice = addError(module, "LatticeError", py::make_tuple(base, valueError),
                            "Bad input to the FFD engine (ffd::LatticeError).");
  errors.cancelled = addError(module, "Cancelled", py::make_tuple(base),
                              "A long computation stopped because its progress callback returned False.");
  errors.widget = addError(module, "WidgetError", py::make_tuple(base, valueError),
                           "A widget model call that cannot be done (widgets::WidgetError); .code names the kind.");
  errors.widgetFile = addError(module, "WidgetFileError", py::make_tuple(base, valueError),
                               "A widget file that cannot be read or written.");
  errors.sceneFile = addError(module, "SceneFileError", py::make_tuple(base, valueError),
                              "A scene file that cannot be read or written.");
  errors.meshIo = addError(module, "MeshIoError", py::make_tuple(base, osError),
                           "A mesh or point file that cannot be read or written.");
  errors.generator = addError(module, "GeneratorError", py::make_tuple(base, valueError),
                              "A generator that cannot run with the given parameters.");
  errors.animation = addError(module, "AnimationError", py::make_tuple(base, valueError),
                              "A key or animation that cannot be set or evaluated (scenes::AnimationError).");

  py::register_exception_translator([](std::exception_ptr pointer) {
    if (!pointer) return;
    try {
      std::rethrow_exception(pointer);
    } catch (const ffd::LatticeError& e) {
      PyErr_SetString(errors.lattice, e.what());
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
  python::bindBoxBernstein(ffdModule);
  py::module_ widgetsModule = module.def_submodule("widgets", "The headless widget model (ffdkit::widgets).");
  python::bindWidgets(widgetsModule);
  py::module_ scenesModule =
      module.def_submodule("scenes", "Scenes, widget and scene files, mesh I/O, generators (ffdkit::scenes).");
  python::bindScenes(scenesModule);
  py::module_ appModule =
      module.def_submodule("app", "Scenes edited as the app edits them, with undo (ffdkit::app's controller).");
  python::bindApp(appModule);
}
