// ffdkit.cad's C++ half (ffdkit._ffdkit._cad): STEP and IGES parts (cad/), their exact FFD, their
// tessellation and their check. Built only with the cad module (FFDKIT_WITH_CAD; without it
// cad_unavailable.cpp); python/ffdkit/cad.py gives the functions their Python names and docstrings.
#include <optional>
#include <string>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "ffdkit/cad/cad_check.h"
#include "ffdkit/cad/cad_deform.h"
#include "ffdkit/cad/cad_error.h"
#include "ffdkit/cad/cad_io.h"
#include "ffdkit/cad/sample_parts.h"
#include "ffdkit/cad/tessellation.h"
#include "numpy_eigen.h"

namespace ffdkit::python {

namespace {

cad::CadReadOptions readOptions(std::optional<double> maxSeconds, bool isolate) {
  cad::CadReadOptions options;
  if (maxSeconds) {
    if (!(*maxSeconds >= 0.0)) throw py::value_error("max_seconds must be >= 0 (0: no limit), got " + std::to_string(*maxSeconds));
    options.maxSeconds = *maxSeconds;
  }
  options.isolate = isolate;
  return options;
}

cad::CadMethod methodOf(const std::string& method) {
  if (method == "exact") return cad::CadMethod::Exact;
  if (method == "poles") return cad::CadMethod::Poles;
  throw py::value_error("method must be 'exact' or 'poles', got '" + method + "'");
}

PyObject* cadErrorClass = nullptr;

}  // namespace

void addCadModule(py::module_& parent, const py::handle& baseError) {
  py::module_ module =
      parent.def_submodule("_cad", "STEP and IGES parts and their exact FFD (ffdkit::cad); see ffdkit.cad.");
  cadErrorClass = PyErr_NewExceptionWithDoc("ffdkit.CadError",
                                            "A CAD file that cannot be read or written, or a deformation the cad module "
                                            "cannot make exactly; also a RuntimeError.\n\nThe message names the file "
                                            "(or the part and face) and what failed.",
                                            py::make_tuple(baseError, py::handle(PyExc_RuntimeError)).ptr(), nullptr);
  if (cadErrorClass == nullptr) throw py::error_already_set();
  module.add_object("CadError", py::handle(cadErrorClass));
  py::register_exception_translator([](std::exception_ptr pointer) {
    if (!pointer) return;
    try {
      std::rethrow_exception(pointer);
    } catch (const cad::CadError& e) {
      PyErr_SetString(cadErrorClass, e.what());
    }
  });

  py::class_<cad::CadModel>(module, "Model", R"doc(A CAD model: named parts, each a B-rep (solid, shell or faces).

Made by read_step, read_iges, deform and make_sample_part; a copy shares its shapes.)doc")
      .def_property_readonly("part_count", &cad::CadModel::partCount, "Number of parts.")
      .def_property_readonly(
          "part_names",
          [](const cad::CadModel& model) {
            std::vector<std::string> names;
            for (int i = 0; i < model.partCount(); ++i) names.push_back(model.partName(i));
            return names;
          },
          "The parts' names (from the file's products or labels; 'part-N' when none).")
      .def_property_readonly(
          "bounds",
          [](const cad::CadModel& model) {
            const Eigen::AlignedBox3d box = model.bounds();
            return py::make_tuple(Eigen::Vector3d(box.min()), Eigen::Vector3d(box.max()));
          },
          "(min, max) corners of the union of the parts' bounding boxes.")
      .def_property_readonly(
          "counts",
          [](const cad::CadModel& model) {
            const cad::CadModel::Counts c = model.counts();
            py::dict d;
            d["solids"] = c.solids;
            d["shells"] = c.shells;
            d["faces"] = c.faces;
            d["edges"] = c.edges;
            d["vertices"] = c.vertices;
            return d;
          },
          "Topology counts: a dict of solids, shells, faces, edges, vertices.");

  module.def(
      "read_step",
      [](const std::filesystem::path& path, std::optional<double> maxSeconds, bool isolate) {
        return cad::readStep(path, readOptions(maxSeconds, isolate));
      },
      py::arg("path"), py::arg("max_seconds") = py::none(), py::arg("isolate") = true,
      "Reads a STEP file (see ffdkit.cad.read_step).\n\nRaises CadError naming the file.");
  module.def(
      "read_iges",
      [](const std::filesystem::path& path, std::optional<double> maxSeconds, bool isolate) {
        return cad::readIges(path, readOptions(maxSeconds, isolate));
      },
      py::arg("path"), py::arg("max_seconds") = py::none(), py::arg("isolate") = true,
      "Reads an IGES file (see ffdkit.cad.read_iges).\n\nRaises CadError naming the file.");
  module.def("write_step", &cad::writeStep, py::arg("model"), py::arg("path"),
             "Writes STEP AP214 (see ffdkit.cad.write_step).\n\nRaises CadError naming the file.");
  module.def("write_iges", &cad::writeIges, py::arg("model"), py::arg("path"),
             "Writes IGES 5.3 (see ffdkit.cad.write_iges).\n\nRaises CadError naming the file.");
  module.def(
      "deform",
      [](const cad::CadModel& model, const ffd::Lattice& lattice, const std::string& method, int maxDegree, int samples) {
        cad::CadDeformOptions options;
        options.method = methodOf(method);
        options.maxDegree = maxDegree;
        options.samples = samples;
        cad::CadDeformResult result = [&] {
          py::gil_scoped_release release;
          return cad::deformCad(model, lattice, options);
        }();
        py::dict report;
        report["faces"] = result.report.faces;
        report["edges"] = result.report.edges;
        report["max_degree"] = result.report.maxDegree;
        report["max_deviation"] = result.report.maxDeviation;
        report["max_gap"] = result.report.maxGap;
        report["seconds"] = result.report.seconds;
        return py::make_tuple(result.model, report);
      },
      py::arg("model"), py::arg("lattice"), py::arg("method") = "exact", py::arg("max_degree") = 15,
      py::arg("samples") = 0, "Deforms a model by a lattice (see ffdkit.cad.deform).\n\nReturns (model, report).");
  module.def(
      "tessellate",
      [](const cad::CadModel& model, double linearDeflection, double angularDeflection, double maxEdgeLength) {
        cad::TessellationOptions options;
        options.linearDeflection = linearDeflection;
        options.angularDeflection = angularDeflection;
        options.maxEdgeLength = maxEdgeLength;
        cad::CadTriangles t = cad::tessellate(model, options);
        Eigen::VectorXi parts = t.partOfTriangle;
        return py::make_tuple(toArray(std::move(t.points)), toArray(std::move(t.triangles)),
                              py::array_t<int>(parts.size(), parts.data()));
      },
      py::arg("model"), py::arg("linear_deflection") = 0.0, py::arg("angular_deflection") = 0.5,
      py::arg("max_edge_length") = 0.0,
      "Triangles of every face (see ffdkit.cad.tessellate).\n\nReturns (points, triangles, part_of_triangle).");
  module.def(
      "check",
      [](const cad::CadModel& model) {
        const cad::CadCheck c = cad::checkModel(model);
        py::dict d;
        d["valid"] = c.valid;
        d["first_problem"] = c.firstProblem;
        d["volume"] = c.volume;
        d["max_tolerance"] = c.maxTolerance;
        return d;
      },
      py::arg("model"), "BRepCheck and volume (see ffdkit.cad.check).\n\nReturns a dict.");
  module.def(
      "enclosed_volume",
      [](const py::object& points, const py::object& triangles) {
        const PointsArg p(points, "points");
        return cad::enclosedVolume(Eigen::MatrixX3d(p.ref()), intRows3(triangles, "triangles"));
      },
      py::arg("points"), py::arg("triangles"), "Volume a closed triangle set encloses (see ffdkit.cad.enclosed_volume).\n\nReturns a float.");
  module.def(
      "make_sample_part",
      [](const std::string& name) {
        for (const cad::SamplePart part : cad::allSampleParts())
          if (cad::samplePartName(part) == name) return cad::makeSamplePart(part);
        std::string known;
        for (const cad::SamplePart part : cad::allSampleParts()) known += (known.empty() ? "" : ", ") + cad::samplePartName(part);
        throw py::value_error("unknown sample part '" + name + "' (known: " + known + ")");
      },
      py::arg("name"), "A part built with OpenCASCADE (see ffdkit.cad.make_sample_part).\n\nRaises ValueError for an unknown name.");
}

}  // namespace ffdkit::python
