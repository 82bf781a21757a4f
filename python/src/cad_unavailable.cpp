// ffdkit._ffdkit without the cad module (FFDKIT_WITH_CAD off): no _cad submodule, so that importing
// ffdkit.cad raises ImportError saying that this build has no OpenCASCADE (python/ffdkit/cad.py).
// With the cad module, cad_bindings.cpp defines addCadModule instead.
//
// bindings.h declares addCadModule; it is not included here, as it would parse all of pybind11
// (about 3.5 s of compiling) for a function that does nothing. A definition that differed from
// its declaration would leave module.cpp's call unresolved, and importing the module would fail
// on the undefined symbol (every Python test imports it).

namespace pybind11 {
class module_;
class handle;
}  // namespace pybind11

namespace ffdkit::python {

void addCadModule(pybind11::module_& /*module*/, const pybind11::handle& /*baseError*/) {}

}  // namespace ffdkit::python
