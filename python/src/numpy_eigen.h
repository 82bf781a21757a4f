#pragma once

// Conversions between numpy arrays and the Eigen types of the public C++ API, shared by the
// binding files. Points are numpy float64 arrays of shape (N, 3). Eigen::MatrixX3d is
// column-major, so a Fortran-ordered (N, 3) array maps without a copy; any other layout or
// dtype is copied once.

#include <functional>
#include <memory>
#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "ffdkit/ffd/embedding.h"

namespace ffdkit::python {

namespace py = pybind11;

/// A read-only (N, 3) float64 view of a numpy argument: the caller's buffer when it is a
/// Fortran-ordered float64 (N, 3) array, otherwise a column-major copy. Keeps the array alive.
class PointsArg {
 public:
  /// @throws py::value_error naming `what` for anything but a 2-d array-like of shape (N, 3)
  ///         (a flat sequence of 3 numbers is one point).
  PointsArg(py::handle object, const char* what);
  Eigen::Ref<const Eigen::MatrixX3d> ref() const;
  Eigen::Index rows() const { return rows_; }
  bool copied() const { return copied_; }

 private:
  py::array array_;
  Eigen::MatrixX3d copy_;
  const double* data_ = nullptr;
  Eigen::Index rows_ = 0;
  bool copied_ = false;
};

/// A view of `matrix` (N x 3, column-major) owned by `owner` (kept alive by the array).
py::array viewOf(const Eigen::MatrixX3d& matrix, py::handle owner, bool writeable);
/// Moves a result into a new numpy array that owns it (no copy of the data).
py::array toArray(Eigen::MatrixX3d&& matrix);
py::array toArray(Eigen::MatrixX3i&& matrix);
py::array toArray(Eigen::MatrixX2i&& matrix);
/// Copies an N x 3 / N x 2 integer matrix from a numpy array (index data, small).
Eigen::MatrixX3i intRows3(py::handle object, const char* what);
Eigen::MatrixX2i intRows2(py::handle object, const char* what);

/// A 4 x 4 homogeneous matrix (last row 0 0 0 1) as an Eigen affine transform; None gives the
/// identity. @throws py::value_error for another shape, a bad last row or non-finite values.
Eigen::Affine3d affineArg(py::handle object, const char* what);
py::array affineToArray(const Eigen::Affine3d& transform);

/// Bridges a Python progress callback to the C++ progress hooks. The hook runs on the thread
/// that called the C++ function (never an OpenMP worker), takes the GIL for the call,
/// treats a return value of None as "go on", and turns a Python exception (or Ctrl-C) into a
/// cancel; call rethrowIfFailed() when ffd::Cancelled arrives to raise that exception instead.
class PythonProgress {
 public:
  explicit PythonProgress(py::object callback);
  bool empty() const { return !state_; }
  /// (done, total) -> bool, for ffd::EmbedOptions and ffd::Pipeline.
  ffd::EmbedProgress embedHook() const;
  /// fraction -> bool, for scenes::SceneDeformer.
  std::function<bool(double)> fractionHook() const;
  /// Raises the Python exception the callback raised, if any. Needs the GIL.
  void rethrowIfFailed() const;

 private:
  struct State {
    py::object callback;
    std::optional<py::error_already_set> error;
  };
  std::shared_ptr<State> state_;
};

}  // namespace ffdkit::python
