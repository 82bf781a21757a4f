// ffdkit.ffd.boxBernsteinDeform: the one-pass box Bernstein FFD (ffd/box_bernstein_deform.h)
// behind ffdkit.pygem.FFD. Points are read in place whatever their layout (C order, Fortran
// order, a slice); the result is a new C-ordered array, or `out`.

#include <cstdint>
#include <string>

#include <pybind11/eigen.h>

#include "bindings.h"
#include "ffdkit/ffd/box_bernstein_deform.h"
#include "numpy_eigen.h"

namespace ffdkit::python {

using namespace pybind11::literals;

namespace {

// A float64 (N, 3) array whose strides are whole doubles (any layout), as strided rows.
struct StridedArray {
  py::array array;
  Eigen::Index rows = 0;
  Eigen::Index rowStride = 3, colStride = 1;  // in doubles
};

std::string shapeOf(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < array.ndim(); ++d) text += (d ? ", " : "") + std::to_string(array.shape(d));
  return text + (array.ndim() == 1 ? ",)" : ")");
}

// Strides the kernel takes as they are: non-negative whole float64 items.
bool wholeDoubleStrides(const py::array& array) {
  constexpr auto size = static_cast<py::ssize_t>(sizeof(double));
  return array.strides(0) >= 0 && array.strides(1) >= 0 && array.strides(0) % size == 0 && array.strides(1) % size == 0 &&
         reinterpret_cast<std::uintptr_t>(array.data()) % alignof(double) == 0;
}

StridedArray stridedArray(py::array array) {
  StridedArray result;
  result.rows = array.shape(0);
  if (result.rows > 0) {
    result.rowStride = array.strides(0) / static_cast<py::ssize_t>(sizeof(double));
    result.colStride = array.strides(1) / static_cast<py::ssize_t>(sizeof(double));
  }
  result.array = std::move(array);
  return result;
}

// The input points: float64 arrays of shape (N, 3) are used in place; other dtypes, odd strides
// and array-likes are converted once. A flat sequence of 3 numbers is one point.
StridedArray pointsArg(const py::object& object, const char* what) {
  auto fail = [&](const std::string& got) {
    throw py::value_error(std::string(what) + ": expected a float64 array of shape (N, 3)" + got);
  };
  py::array array = py::array::ensure(object);
  if (!array) fail(", got a " + std::string(py::str(py::type::of(object).attr("__name__"))));
  if (array.ndim() == 1 && (array.shape(0) == 3 || array.shape(0) == 0)) array = array.attr("reshape")(-1, 3);
  if (array.ndim() != 2 || array.shape(1) != 3) fail(", got shape " + shapeOf(array));
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') fail(", got dtype " + std::string(py::str(array.dtype())));
  if (!array.dtype().equal(py::dtype::of<double>()) || !wholeDoubleStrides(array)) {
    array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  }
  return stridedArray(std::move(array));
}

StridedArray outArg(const py::object& object, Eigen::Index rows) {
  if (object.is_none()) return stridedArray(py::array_t<double>({static_cast<py::ssize_t>(rows), py::ssize_t(3)}));
  py::array array = py::array::ensure(object);
  if (!array || !array.dtype().equal(py::dtype::of<double>()) || array.ndim() != 2 || array.shape(0) != rows ||
      array.shape(1) != 3) {
    throw py::value_error("out: expected a float64 array of shape (" + std::to_string(rows) + ", 3)" +
                          (array ? ", got " + std::string(py::str(array.dtype())) + " " + shapeOf(array) : ""));
  }
  if (!array.writeable()) throw py::value_error("out: the array is read-only");
  if (!wholeDoubleStrides(array)) throw py::value_error("out: strides must be non-negative whole float64 items");
  return stridedArray(std::move(array));
}

// [first, last] byte of an array's elements (strides are non-negative).
std::pair<std::uintptr_t, std::uintptr_t> byteRange(const StridedArray& a) {
  const auto base = reinterpret_cast<std::uintptr_t>(a.array.data());
  const auto extent = static_cast<std::uintptr_t>(((a.rows - 1) * a.rowStride + 2 * a.colStride) * Eigen::Index(sizeof(double)));
  return {base, base + extent + sizeof(double) - 1};
}

py::array boxBernsteinDeform(const ffd::BoxBernsteinLattice& lattice, const py::object& points,
                             const py::object& options, const py::object& out) {
  const StridedArray in = pointsArg(points, "points");
  StridedArray result = outArg(out, in.rows);
  const ffd::BoxBernsteinDeformOptions opts =
      options.is_none() ? ffd::BoxBernsteinDeformOptions{} : options.cast<ffd::BoxBernsteinDeformOptions>();
  if (in.rows == 0) return result.array;
  const bool same = in.array.data() == result.array.data() && in.rowStride == result.rowStride &&
                    in.colStride == result.colStride;
  const auto [inFirst, inLast] = byteRange(in);
  const auto [outFirst, outLast] = byteRange(result);
  if (!same && inFirst <= outLast && outFirst <= inLast) {
    throw py::value_error("out: shares memory with points without being the same array (in place needs out=points)");
  }
  const Eigen::Map<const ffd::PointRows, 0, ffd::PointRowsStride> q(
      static_cast<const double*>(in.array.data()), in.rows, 3, ffd::PointRowsStride(in.rowStride, in.colStride));
  Eigen::Map<ffd::PointRows, 0, ffd::PointRowsStride> o(static_cast<double*>(result.array.mutable_data()), in.rows, 3,
                                                        ffd::PointRowsStride(result.rowStride, result.colStride));
  {
    py::gil_scoped_release release;
    ffd::boxBernsteinDeform(lattice, q, o, opts);
  }
  return result.array;
}

}  // namespace

void bindBoxBernstein(py::module_& m) {
  py::class_<ffd::BoxBernsteinLattice>(m, "BoxBernsteinLattice", R"doc(A Bernstein lattice on an oriented box, given by its control-point displacements (ffd/box_bernstein_deform.h).

The kernel behind ffdkit.pygem.FFD. Fields: counts (l, m, n), frame (4 x 4: the box's edge vectors
as the columns of its linear part, its origin as translation), displacements ((l*m*n) x 3 in box
coordinates, flat index i + l*(j + m*k)).)doc")
      .def(py::init([](const Eigen::Vector3i& counts, const py::object& frame, const py::object& displacements) {
             ffd::BoxBernsteinLattice lattice;
             lattice.counts = counts;
             lattice.frame = affineArg(frame, "frame");
             if (!displacements.is_none()) {
               lattice.displacements = displacements.cast<Eigen::MatrixX3d>();
             }
             return lattice;
           }),
           "counts"_a = Eigen::Vector3i(2, 2, 2), "frame"_a = py::none(), "displacements"_a = py::none(), R"doc(A box lattice.

Args:
    counts: control points per axis (default 2, 2, 2).
    frame: 4 x 4 box frame (default the unit box).
    displacements: (l*m*n) x 3 control-point moves in box coordinates (default zeros).
Raises:
    ValueError: a frame that is not 4 x 4 (sizes are checked by boxBernsteinDeform).)doc")
      .def_readwrite("counts", &ffd::BoxBernsteinLattice::counts)
      .def_property(
          "frame", [](const ffd::BoxBernsteinLattice& l) { return affineToArray(l.frame); },
          [](ffd::BoxBernsteinLattice& l, const py::object& frame) { l.frame = affineArg(frame, "frame"); })
      .def_readwrite("displacements", &ffd::BoxBernsteinLattice::displacements);

  py::class_<ffd::BoxBernsteinDeformOptions>(m, "BoxBernsteinDeformOptions", R"doc(Options of boxBernsteinDeform.

BoxBernsteinDeformOptions(faceTolerance=1e-12, parallel=True): box coordinates within
faceTolerance of a face count as on it; parallel runs on all OpenMP threads.)doc")
      .def(py::init([](double faceTolerance, bool parallel) {
             return ffd::BoxBernsteinDeformOptions{faceTolerance, parallel};
           }),
           "faceTolerance"_a = 1e-12, "parallel"_a = true, R"doc(Options.

Args:
    faceTolerance: box coordinates within this of [0, 1] count as inside.
    parallel: run on all OpenMP threads.)doc")
      .def_readwrite("faceTolerance", &ffd::BoxBernsteinDeformOptions::faceTolerance)
      .def_readwrite("parallel", &ffd::BoxBernsteinDeformOptions::parallel);

  m.def("boxBernsteinDeform", &boxBernsteinDeform, "lattice"_a, "points"_a, "options"_a = py::none(),
        "out"_a = py::none(), R"doc(One-pass FFD by a Bernstein box lattice: points inside the box move, the others are copied.

Nothing is stored per point; the interpreter lock is released.
Args:
    lattice: BoxBernsteinLattice.
    points: (N, 3) float array of any layout, read in place.
    options: BoxBernsteinDeformOptions (default: BoxBernsteinDeformOptions()).
    out: where to write: None (a new C-ordered (N, 3) array), any writable float64 (N, 3)
        array, or points itself to deform in place.
Returns:
    out.
Raises:
    ValueError: points or out of the wrong shape or dtype, out read-only or overlapping points.
    LatticeError: counts or displacements that do not match.)doc");
}

}  // namespace ffdkit::python
