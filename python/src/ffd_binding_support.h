// Helpers shared by the ffdkit.ffd binding files (ffd_bindings.cpp, ffd_pipeline_bindings.cpp,
// shape_constraints_bindings.cpp).
#pragma once

#include <Eigen/Core>
#include <pybind11/pybind11.h>

#include "ffdkit/ffd/cancelled.h"
#include "ffdkit/ffd/lattice.h"
#include "numpy_eigen.h"

namespace ffdkit::python {

// The control points of a Python-side lattice are a writable numpy view: writes through it do
// not pass Lattice::setControlPoints, so every call that reads them first validates them and
// bumps the revision (a copy of l*m*n points, negligible beside any evaluation).
inline ffd::Lattice& synced(ffd::Lattice& lattice) {
  lattice.setControlPoints(Eigen::MatrixX3d(lattice.controlPoints()));
  return lattice;
}

// Runs `work` without the GIL; a Python exception raised by the progress callback replaces
// the Cancelled it caused.
template <typename Work>
auto withoutGil(const PythonProgress& progress, Work&& work) {
  try {
    py::gil_scoped_release release;
    return work();
  } catch (const ffd::Cancelled&) {
    progress.rethrowIfFailed();
    throw;
  }
}

}  // namespace ffdkit::python
