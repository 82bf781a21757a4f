#include "numpy_eigen.h"

#include <string>
#include <utility>

namespace ffdkit::python {

namespace {

std::string shapeText(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < array.ndim(); ++d) {
    text += (d ? ", " : "") + std::to_string(array.shape(d));
  }
  return text + (array.ndim() == 1 ? ",)" : ")");
}

template <typename Matrix>
py::array ownedArray(Matrix&& matrix, py::dtype dtype) {
  using Scalar = typename std::decay_t<Matrix>::Scalar;
  auto* owned = new std::decay_t<Matrix>(std::move(matrix));
  py::capsule free(owned, [](void* p) { delete static_cast<std::decay_t<Matrix>*>(p); });
  const auto rows = static_cast<py::ssize_t>(owned->rows());
  const auto cols = static_cast<py::ssize_t>(owned->cols());
  const auto item = static_cast<py::ssize_t>(sizeof(Scalar));
  return py::array(dtype, {rows, cols}, {item, item * rows}, owned->data(), free);
}

template <typename Matrix>
Matrix intRows(py::handle object, const char* what) {
  constexpr int kCols = Matrix::ColsAtCompileTime;
  auto array = py::array_t<long long, py::array::forcecast>::ensure(object);
  const bool empty = array && array.size() == 0 && array.ndim() <= 2;
  if (!array || (!empty && !(array.ndim() == 2 && array.shape(1) == kCols))) {
    throw py::value_error(std::string(what) + ": expected an integer array of shape (N, " +
                          std::to_string(kCols) + ")" + (array ? ", got shape " + shapeText(array) : ""));
  }
  const Eigen::Index rows = empty ? 0 : array.shape(0);
  Matrix result(rows, kCols);
  if (rows > 0) {
    auto view = array.template unchecked<2>();
    for (Eigen::Index r = 0; r < rows; ++r) {
      for (int c = 0; c < kCols; ++c) {
        const long long v = view(r, c);
        if (v < 0 || v > 0x7fffffff) {
          throw py::value_error(std::string(what) + ": index " + std::to_string(v) + " at row " +
                                std::to_string(r) + " is out of range");
        }
        result(r, c) = static_cast<int>(v);
      }
    }
  }
  return result;
}

}  // namespace

PointsArg::PointsArg(py::handle object, const char* what) {
  auto fail = [&](const std::string& got) {
    throw py::value_error(std::string(what) + ": expected a float64 array of shape (N, 3)" + got);
  };
  array_ = py::array::ensure(object);
  if (!array_) fail(", got a " + std::string(py::str(py::type::of(object).attr("__name__"))));
  if (array_.ndim() == 1 && array_.shape(0) == 3) array_ = array_.attr("reshape")(1, 3);
  if (array_.ndim() == 1 && array_.shape(0) == 0) array_ = array_.attr("reshape")(0, 3);
  if (array_.ndim() != 2 || array_.shape(1) != 3) fail(", got shape " + shapeText(array_));
  const char kind = array_.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') fail(", got dtype " + std::string(py::str(array_.dtype())));
  rows_ = array_.shape(0);
  const bool fortranDouble =
      array_.dtype().equal(py::dtype::of<double>()) && (array_.flags() & py::array::f_style) != 0;
  if (fortranDouble || rows_ == 0) {
    data_ = rows_ ? static_cast<const double*>(array_.data()) : nullptr;
    if (rows_ == 0) copy_.resize(0, 3);
    return;
  }
  copied_ = true;
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  if (array_.dtype().equal(py::dtype::of<double>()) && (array_.flags() & py::array::c_style) != 0) {
    copy_ = Eigen::Map<const RowMajor>(static_cast<const double*>(array_.data()), rows_, 3);  // numpy's default layout
    return;
  }
  auto doubles = py::array_t<double, py::array::forcecast>::ensure(array_);
  auto view = doubles.unchecked<2>();
  copy_.resize(rows_, 3);
  for (Eigen::Index r = 0; r < rows_; ++r) {
    for (int c = 0; c < 3; ++c) copy_(r, c) = view(r, c);
  }
}

Eigen::Ref<const Eigen::MatrixX3d> PointsArg::ref() const {
  if (copied_ || rows_ == 0) return copy_;
  return Eigen::Map<const Eigen::MatrixX3d>(data_, rows_, 3);
}

py::array viewOf(const Eigen::MatrixX3d& matrix, py::handle owner, bool writeable) {
  const auto rows = static_cast<py::ssize_t>(matrix.rows());
  const auto item = static_cast<py::ssize_t>(sizeof(double));
  py::array view(py::dtype::of<double>(), {rows, py::ssize_t(3)}, {item, item * rows}, matrix.data(), owner);
  if (!writeable) py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return view;
}

py::array toArray(Eigen::MatrixX3d&& matrix) { return ownedArray(std::move(matrix), py::dtype::of<double>()); }
py::array toArray(Eigen::MatrixX3i&& matrix) { return ownedArray(std::move(matrix), py::dtype::of<int>()); }
py::array toArray(Eigen::MatrixX2i&& matrix) { return ownedArray(std::move(matrix), py::dtype::of<int>()); }

Eigen::MatrixX3i intRows3(py::handle object, const char* what) { return intRows<Eigen::MatrixX3i>(object, what); }
Eigen::MatrixX2i intRows2(py::handle object, const char* what) { return intRows<Eigen::MatrixX2i>(object, what); }

Eigen::Affine3d affineArg(py::handle object, const char* what) {
  if (object.is_none()) return Eigen::Affine3d::Identity();
  auto array = py::array_t<double, py::array::forcecast>::ensure(object);
  if (!array || array.ndim() != 2 || array.shape(0) != 4 || array.shape(1) != 4) {
    throw py::value_error(std::string(what) + ": expected a 4 x 4 homogeneous matrix" +
                          (array ? ", got shape " + shapeText(array) : ""));
  }
  auto view = array.unchecked<2>();
  Eigen::Affine3d transform;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) transform.matrix()(r, c) = view(r, c);
  }
  if (!transform.matrix().allFinite()) throw py::value_error(std::string(what) + ": the matrix is not finite");
  if (transform.matrix().row(3) != Eigen::RowVector4d(0, 0, 0, 1)) {
    throw py::value_error(std::string(what) + ": the last row of a homogeneous matrix must be (0, 0, 0, 1)");
  }
  return transform;
}

py::array affineToArray(const Eigen::Affine3d& transform) {
  py::array_t<double> result({4, 4});
  auto view = result.mutable_unchecked<2>();
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) view(r, c) = transform.matrix()(r, c);
  }
  return result;
}

PythonProgress::PythonProgress(py::object callback) {
  if (callback.is_none()) return;
  if (!PyCallable_Check(callback.ptr())) throw py::type_error("progress: expected a callable or None");
  // The last reference may be dropped where the GIL is released (a C++ copy of the hook):
  // take it before the Python callable is released.
  state_ = std::shared_ptr<State>(new State{std::move(callback), std::nullopt}, [](State* state) {
    py::gil_scoped_acquire gil;
    delete state;
  });
}

namespace {
// None (a callback that only reports) goes on, like True.
bool goesOn(const py::object& result) { return result.is_none() || py::cast<bool>(result); }
}  // namespace

ffd::EmbedProgress PythonProgress::embedHook() const {
  if (!state_) return {};
  return [state = state_](Eigen::Index done, Eigen::Index total) -> bool {
    py::gil_scoped_acquire gil;
    if (state->error) return false;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      return goesOn(state->callback(done, total));
    } catch (py::error_already_set& error) {
      state->error.emplace(std::move(error));
      return false;
    }
  };
}

std::function<bool(double)> PythonProgress::fractionHook() const {
  if (!state_) return {};
  return [state = state_](double fraction) -> bool {
    py::gil_scoped_acquire gil;
    if (state->error) return false;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      return goesOn(state->callback(fraction));
    } catch (py::error_already_set& error) {
      state->error.emplace(std::move(error));
      return false;
    }
  };
}

void PythonProgress::rethrowIfFailed() const {
  if (!state_ || !state_->error) return;
  py::error_already_set error = std::move(*state_->error);
  state_->error.reset();
  throw error;
}

}  // namespace ffdkit::python
