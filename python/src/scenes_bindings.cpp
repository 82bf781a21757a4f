// ffdkit.scenes: scenes and their files, widget files, mesh I/O, the generators by name and the
// scene deformer (scenes/include/ffdkit/scenes). Names mirror the C++ API.

#include <filesystem>
#include <optional>
#include <string>
#include <utility>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "ffdkit/scenes/generator.h"
#include "ffdkit/scenes/mesh_io.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/scene_file.h"
#include "ffdkit/scenes/widget_file.h"
#include "numpy_eigen.h"

namespace ffdkit::python {

using namespace pybind11::literals;

namespace {

// A generator parameter from Python: bool, number, str, a list of numbers or a list of rows.
// (pybind11's variant caster would turn an int into a bool: the first alternative that converts.)
scenes::ParameterValue parameterValue(const std::string& name, const py::handle value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)) return value.cast<double>();
  auto array = py::array_t<double, py::array::forcecast>::ensure(value);
  if (array && array.ndim() == 1) return value.cast<std::vector<double>>();
  if (array && array.ndim() == 2) {
    std::vector<std::vector<double>> rows(static_cast<std::size_t>(array.shape(0)));
    auto view = array.unchecked<2>();
    for (py::ssize_t r = 0; r < array.shape(0); ++r) {
      for (py::ssize_t c = 0; c < array.shape(1); ++c) rows[static_cast<std::size_t>(r)].push_back(view(r, c));
    }
    return rows;
  }
  throw py::value_error("generator parameter '" + name +
                        "': expected a bool, a number, a str, a list of numbers or a list of rows of numbers");
}

scenes::GeneratorParameters generatorParameters(const py::dict& parameters) {
  scenes::GeneratorParameters result;
  for (const auto& [key, value] : parameters) {
    const std::string name = py::str(key);
    result.set(name, parameterValue(name, value));
  }
  return result;
}

// The scene deformer together with the Python progress callback it was given, so that an
// exception raised by the callback is re-raised instead of the Cancelled it caused.
struct SceneDeformerHandle {
  scenes::SceneDeformer deformer;
  PythonProgress progress{py::none()};

  template <typename Work>
  void run(Work&& work) {
    try {
      py::gil_scoped_release release;
      work();
    } catch (const ffd::Cancelled&) {
      progress.rethrowIfFailed();
      throw;
    }
  }
};

void bindMeshes(py::module_& m) {
  py::class_<scenes::MeshData>(m, "MeshData", "Points with triangles or segments (scenes/mesh_io.h).")
      .def(py::init([](const py::object& points, const py::object& triangles, const py::object& segments, bool normals) {
             scenes::MeshData mesh;
             mesh.points = PointsArg(points, "points").ref();
             if (!triangles.is_none()) mesh.triangles = intRows3(triangles, "triangles");
             if (!segments.is_none()) mesh.segments = intRows2(segments, "segments");
             mesh.hasNormals = normals;
             return mesh;
           }),
           "points"_a, "triangles"_a = py::none(), "segments"_a = py::none(), "hasNormals"_a = false)
      .def_property(
          "points", [](py::object self) { return viewOf(self.cast<scenes::MeshData&>().points, self, true); },
          [](scenes::MeshData& mesh, const py::object& points) { mesh.points = PointsArg(points, "points").ref(); },
          "#P x 3 (a writable view)")
      .def_property(
          "triangles", [](const scenes::MeshData& mesh) { return toArray(Eigen::MatrixX3i(mesh.triangles)); },
          [](scenes::MeshData& mesh, const py::object& t) { mesh.triangles = intRows3(t, "triangles"); }, "#T x 3 (a copy)")
      .def_property(
          "segments", [](const scenes::MeshData& mesh) { return toArray(Eigen::MatrixX2i(mesh.segments)); },
          [](scenes::MeshData& mesh, const py::object& s) { mesh.segments = intRows2(s, "segments"); }, "#S x 2 (a copy)")
      .def_readwrite("hasNormals", &scenes::MeshData::hasNormals)
      .def("__repr__", [](const scenes::MeshData& mesh) {
        return "<ffdkit.scenes.MeshData " + std::to_string(mesh.points.rows()) + " points, " +
               std::to_string(mesh.triangles.rows()) + " triangles, " + std::to_string(mesh.segments.rows()) +
               " segments>";
      });
  // Lambdas: readMesh and writeMesh also have stream overloads.
  m.def("readMesh", [](const std::filesystem::path& path) { return scenes::readMesh(path); }, "path"_a,
        py::call_guard<py::gil_scoped_release>(),
        "Reads .obj .ply .stl .vtp .vtk .gltf/.glb .xyz .npy by extension, checked while it parses.");
  m.def("writeMesh", [](const std::filesystem::path& path, const scenes::MeshData& mesh) { scenes::writeMesh(path, mesh); },
        "path"_a, "mesh"_a, py::call_guard<py::gil_scoped_release>(),
        "Writes .obj .ply .stl .vtp .vtk .xyz .npy by extension, atomically.");
  m.def("validateMesh", &scenes::validateMesh, "mesh"_a, "what"_a = "mesh");
}

void bindGenerators(py::module_& m) {
  m.def("generatorNames", [] { return scenes::builtinGenerators().names(); });
  m.def("generatorSummary", [](const std::string& name) { return scenes::builtinGenerators().get(name).summary; },
        "name"_a);
  m.def("generatorParameterNames",
        [](const std::string& name) { return scenes::builtinGenerators().get(name).parameterNames; }, "name"_a);
  m.def("generate",
        [](const std::string& name, const py::dict& parameters, double density) {
          const scenes::GeneratorParameters values = generatorParameters(parameters);
          py::gil_scoped_release release;
          return scenes::builtinGenerators().generate(name, values, density);
        },
        "name"_a, "parameters"_a = py::dict(), "density"_a = 1.0,
        "Runs a built-in generator by name (docs/generators.md) and returns its MeshData.");
}

void bindSceneDocuments(py::module_& m) {
  py::class_<scenes::SceneObject>(m, "SceneObject")
      .def_readonly("name", &scenes::SceneObject::name)
      .def_readonly("mesh", &scenes::SceneObject::mesh, "The object's own (undeformed) points (Scene.setObjectMesh changes them).");
  py::class_<scenes::Attachment>(m, "Attachment")
      .def_readonly("lattice", &scenes::Attachment::lattice, "The root lattice's WidgetId (a rename keeps it).")
      .def_readonly("objects", &scenes::Attachment::objects);

  py::class_<scenes::Scene>(m, "Scene", "Objects, the widget model deforming them, attachments (scenes/scene.h).")
      .def(py::init<>())
      .def_readwrite("description", &scenes::Scene::description)
      .def_readwrite("widgets", &scenes::Scene::widgets)
      .def_property_readonly("attachments", &scenes::Scene::attachments)
      .def_readwrite("widgetFile", &scenes::Scene::widgetFile)
      .def("objectNames",
           [](const scenes::Scene& scene) {
             std::vector<std::string> names;
             for (const auto& object : scene.objects()) names.push_back(object.name);
             return names;
           })
      .def("findObject", &scenes::Scene::findObject, py::return_value_policy::reference_internal, "name"_a)
      .def(
          "setObjectMesh",
          [](scenes::Scene& scene, const std::string& name, scenes::MeshData mesh) { scene.setObjectMesh(name, std::move(mesh)); },
          "name"_a, "mesh"_a, "Replaces an object's own points (a deformer notices through the object's revision).")
      .def("latticesDeforming", &scenes::Scene::latticesDeforming, "object"_a)
      .def("validate", &scenes::validateScene);

  m.def("readScene", py::overload_cast<const std::filesystem::path&>(&scenes::readScene), "path"_a,
        py::call_guard<py::gil_scoped_release>(), "Reads a scene file, or <folder>/scene.json.");
  m.def("writeScene", py::overload_cast<const std::filesystem::path&, const scenes::Scene&>(&scenes::writeScene),
        "path"_a, "scene"_a, py::call_guard<py::gil_scoped_release>());
  m.def("sceneFileText", &scenes::sceneFileText, "scene"_a);
  m.def("readWidgetFile", py::overload_cast<const std::filesystem::path&>(&scenes::readWidgetFile), "path"_a,
        py::call_guard<py::gil_scoped_release>());
  m.def("writeWidgetFile",
        py::overload_cast<const std::filesystem::path&, const widgets::WidgetModel&>(&scenes::writeWidgetFile), "path"_a,
        "model"_a, py::call_guard<py::gil_scoped_release>());
  m.def("widgetFileText", &scenes::widgetFileText, "model"_a);

  py::class_<scenes::SceneDeformStats>(m, "SceneDeformStats")
      .def_readonly("seconds", &scenes::SceneDeformStats::seconds)
      .def_readonly("reembeddedStages", &scenes::SceneDeformStats::reembeddedStages)
      .def_readonly("deformedPoints", &scenes::SceneDeformStats::deformedPoints)
      .def_readonly("outsidePoints", &scenes::SceneDeformStats::outsidePoints)
      .def_readonly("failedPoints", &scenes::SceneDeformStats::failedPoints)
      .def_readonly("embedSeconds", &scenes::SceneDeformStats::embedSeconds)
      .def_readonly("latticesBuilt", &scenes::SceneDeformStats::latticesBuilt)
      .def_readonly("deltaStages", &scenes::SceneDeformStats::deltaStages);

  py::class_<scenes::GestureMotion>(m, "GestureMotion",
                                    "How an object's points moved by delta steps of its last lattice stage since their "
                                    "base: points = base + sum_c controlWeights(object, controlPoints[c]) * displacements[c].")
      .def_readonly("baseRevision", &scenes::GestureMotion::baseRevision)
      .def_readonly("lattice", &scenes::GestureMotion::lattice)
      .def_readonly("controlPoints", &scenes::GestureMotion::controlPoints)
      .def_readonly("displacements", &scenes::GestureMotion::displacements);

  py::class_<SceneDeformerHandle>(m, "SceneDeformer",
                                  "Evaluates a scene's lattice trees per object (scenes/scene_deformer.h).")
      .def(py::init<>())
      .def("update",
           [](SceneDeformerHandle& h, const scenes::Scene& scene, std::optional<widgets::WidgetId> active) {
             h.run([&] { h.deformer.update(scene, active); });
           },
           "scene"_a, "activeLattice"_a = py::none(), "Brings every object's deformed points up to date (GIL released).")
      .def("updateGesture",
           [](SceneDeformerHandle& h, const scenes::Scene& scene, std::optional<widgets::WidgetId> active) {
             h.run([&] { h.deformer.updateGesture(scene, active); });
           },
           "scene"_a, "activeLattice"_a = py::none(),
           "One step of a gesture: as update(), but a lattice whose control points moved is updated by deltas "
           "(exact to rounding only, until finishGesture() or update()). GIL released.")
      .def("finishGesture", [](SceneDeformerHandle& h, const scenes::Scene& scene) {
        h.run([&] { h.deformer.finishGesture(scene); });
      }, "scene"_a, "Ends a gesture: evaluates every lattice updated by deltas in full (the exact result).")
      .def("revision", [](const SceneDeformerHandle& h, const std::string& object) { return h.deformer.revision(object); },
           "object"_a, "Grows whenever the object's deformed points change.")
      .def("gestureMotion",
           [](const SceneDeformerHandle& h, const std::string& object) { return h.deformer.gestureMotion(object); },
           "object"_a, "The object's motion by delta steps of its last lattice stage since its base, or None.")
      .def("controlWeights",
           [](const SceneDeformerHandle& h, const std::string& object, Eigen::Index controlPoint) {
             return h.deformer.controlWeights(object, controlPoint);
           },
           "object"_a, "controlPoint"_a,
           "The weight of a control point of the object's last lattice stage for each of its points.")
      .def("setProgress",
           [](SceneDeformerHandle& h, const py::object& callback) {
             h.progress = PythonProgress(callback);
             h.deformer.setProgress(h.progress.fractionHook());
           },
           "progress"_a, "progress(fraction) -> bool|None, called on the updating thread; False or an exception cancels.")
      .def("points",
           [](py::object self, const std::string& object) {
             return viewOf(self.cast<SceneDeformerHandle&>().deformer.points(object), self, false);
           },
           "object"_a, "Deformed points of an object (a read-only view, rewritten by the next update).")
      .def_property_readonly("lastStats", [](const SceneDeformerHandle& h) { return h.deformer.lastStats(); })
      .def("reset", [](SceneDeformerHandle& h) { h.deformer.reset(); });

  m.def("deformScene",
        [](const scenes::Scene& scene) {
          std::map<std::string, Eigen::MatrixX3d> points;
          {
            py::gil_scoped_release release;
            points = scenes::deformScene(scene);
          }
          py::dict result;
          for (auto& [name, matrix] : points) result[py::str(name)] = toArray(std::move(matrix));
          return result;
        },
        "scene"_a, "The deformed points of every object, by name.");
}

}  // namespace

void bindScenes(py::module_& module) {
  bindMeshes(module);
  bindGenerators(module);
  bindAnimationTypes(module);
  bindSceneDocuments(module);
  bindSceneEditing(module);
}

}  // namespace ffdkit::python
