// ffdkit.scenes: scenes and their files, widget files, mesh I/O, the generators by name and the
// scene deformer (scenes/include/ffdkit/scenes). Names mirror the C++ API.

#include <filesystem>
#include <optional>
#include <string>
#include <utility>

#include <pybind11/eigen.h>
#include <pybind11/operators.h>
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
  py::class_<scenes::MeshData>(m, "MeshData", R"doc(Points with triangles or segments: an object's geometry, as the mesh readers return it.

MeshData(points, triangles=None, segments=None, hasNormals=False). points is a writable
#P x 3 view; triangles (#T x 3) and segments (#S x 2) are copies on read; hasNormals: the file
had normals (writers recompute them).)doc")
      .def(py::init([](const py::object& points, const py::object& triangles, const py::object& segments, bool normals) {
             scenes::MeshData mesh;
             mesh.points = PointsArg(points, "points").ref();
             if (!triangles.is_none()) mesh.triangles = intRows3(triangles, "triangles");
             if (!segments.is_none()) mesh.segments = intRows2(segments, "segments");
             mesh.hasNormals = normals;
             return mesh;
           }),
           "points"_a, "triangles"_a = py::none(), "segments"_a = py::none(), "hasNormals"_a = false, R"doc(A mesh from arrays.

Args:
    points: #P x 3 float.
    triangles: #T x 3 point indices, or None.
    segments: #S x 2 point indices, or None.
    hasNormals: write recomputed normals.
Raises:
    ValueError: arrays of the wrong shape (validateMesh checks the indices).)doc")
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
        py::call_guard<py::gil_scoped_release>(), R"doc(Reads a mesh or point file; the extension picks the format, and it is checked while it parses.

Args:
    path: .obj .ply .stl .vtp .vtk .gltf/.glb .xyz or .npy.
Returns:
    MeshData. The interpreter lock is released while it reads.
Raises:
    MeshIoError: the file cannot be read; the message names the file and the element or line.)doc");
  m.def("writeMesh", [](const std::filesystem::path& path, const scenes::MeshData& mesh) { scenes::writeMesh(path, mesh); },
        "path"_a, "mesh"_a, py::call_guard<py::gil_scoped_release>(), R"doc(Writes a mesh atomically (a temporary file renamed over the target); the extension picks the format.

Args:
    path: .obj .ply .stl .vtp .vtk .xyz or .npy.
    mesh: MeshData.
Raises:
    MeshIoError: an unknown extension, an invalid mesh, or a failed write (nothing is left behind).)doc");
  m.def("validateMesh", &scenes::validateMesh, "mesh"_a, "what"_a = "mesh", R"doc(Checks a mesh: shapes, index ranges and finite points.

Args:
    mesh: MeshData.
    what: the name used in the message.
Raises:
    MeshIoError: naming the first offending point or element.)doc");
}

void bindGenerators(py::module_& m) {
  m.def("generatorNames", [] { return scenes::builtinGenerators().names(); }, R"doc(The names of the built-in curve and surface generators (docs/generators.md).

Returns:
    list of str, sorted.)doc");
  m.def("generatorSummary", [](const std::string& name) { return scenes::builtinGenerators().get(name).summary; },
        "name"_a, R"doc(One line describing a generator.

Args:
    name: a generator name.
Raises:
    GeneratorError: an unknown generator (the message lists the known ones).)doc");
  m.def("generatorParameterNames",
        [](const std::string& name) { return scenes::builtinGenerators().get(name).parameterNames; }, "name"_a, R"doc(The parameters a generator accepts.

Args:
    name: a generator name.
Returns:
    list of str.
Raises:
    GeneratorError: an unknown generator.)doc");
  m.def("generate",
        [](const std::string& name, const py::dict& parameters, double density) {
          const scenes::GeneratorParameters values = generatorParameters(parameters);
          py::gil_scoped_release release;
          return scenes::builtinGenerators().generate(name, values, density);
        },
        "name"_a, "parameters"_a = py::dict(), "density"_a = 1.0, R"doc(Runs a built-in generator and returns its curve or surface.

Args:
    name: a generator name (generatorNames()).
    parameters: dict of its parameters (numbers, lists, strings, bools); unknown names are refused.
    density: sampling relative to the generator's default, (0, 64].
Returns:
    MeshData. The interpreter lock is released while it runs.
Raises:
    GeneratorError: an unknown generator or parameter, a bad value, or a solve that fails.)doc");
}

void bindSceneDocuments(py::module_& m) {
  py::class_<scenes::ObjectId>(m, "ObjectId", R"doc(The handle of an object in one Scene; printed as o<N>.

The scene gives it when the object is added and keeps it through renames (a name is a label);
attachments hold ids. Hashable and ordered; value is the number.)doc")
      .def_readonly("value", &scenes::ObjectId::value)
      .def(py::self == py::self)
      .def(py::self < py::self)
      .def("__hash__", [](const scenes::ObjectId& id) { return std::hash<std::uint32_t>{}(id.value); })
      .def("__repr__", [](const scenes::ObjectId& id) { return scenes::toString(id); });
  py::class_<scenes::SceneObject>(m, "SceneObject", R"doc(A deformable object of a Scene (read-only; Scene.findObject returns it).

Fields: id (its ObjectId, which a rename keeps), name, mesh (its own, undeformed points;
Scene.setObjectMesh changes them).)doc")
      .def_readonly("id", &scenes::SceneObject::id)
      .def_readonly("name", &scenes::SceneObject::name)
      .def_readonly("mesh", &scenes::SceneObject::mesh, "The object's own (undeformed) points (Scene.setObjectMesh changes them).");
  py::class_<scenes::Attachment>(m, "Attachment", R"doc(A root lattice (with its subtree) deforming some objects of a Scene.

Fields: lattice (the root lattice's WidgetId, which a rename keeps), objects (ObjectIds, which
renames keep; Scene.objectName gives a name).)doc")
      .def_readonly("lattice", &scenes::Attachment::lattice, "The root lattice's WidgetId (a rename keeps it).")
      .def_readonly("objects", &scenes::Attachment::objects, "The objects' ObjectIds (renames keep them).");

  py::class_<scenes::Scene>(m, "Scene", R"doc(A document: objects, the widget model whose lattices deform them, attachments, camera, animation.

Read one with readScene(); edit widgets through scene.widgets (a WidgetModel) and objects with
the Scene methods; deformScene() or a SceneDeformer gives the deformed points (scenes/scene.h).)doc")
      .def(py::init<>(), R"doc(An empty scene.

Add objects with addMeshFile and lattices with attachNewLattice, or read one with readScene().)doc")
      .def_readwrite("description", &scenes::Scene::description)
      .def_readwrite("widgets", &scenes::Scene::widgets)
      .def_property_readonly("attachments", &scenes::Scene::attachments)
      .def_readwrite("widgetFile", &scenes::Scene::widgetFile)
      .def("objectNames",
           [](const scenes::Scene& scene) {
             std::vector<std::string> names;
             for (const auto& object : scene.objects()) names.push_back(object.name);
             return names;
           }, R"doc(The objects' names, in scene order.

Returns:
    list of str.)doc")
      .def("objectName", &scenes::Scene::objectName, "id"_a, R"doc(The name of the object with this id.

Args:
    id: an ObjectId.
Returns:
    str.
Raises:
    ValueError: no object has this id.)doc")
      .def("objectId", &scenes::Scene::objectId, "name"_a, R"doc(The id of the object with this name.

Args:
    name: the object's name.
Returns:
    ObjectId.
Raises:
    ValueError: an unknown name.)doc")
      .def("findObject", py::overload_cast<const std::string&>(&scenes::Scene::findObject, py::const_),
           py::return_value_policy::reference_internal, "name"_a, R"doc(The object of that name.

Args:
    name: the object's name.
Returns:
    SceneObject, or None when there is none.)doc")
      .def(
          "setObjectMesh",
          [](scenes::Scene& scene, const std::string& name, scenes::MeshData mesh) { scene.setObjectMesh(name, std::move(mesh)); },
          "name"_a, "mesh"_a, R"doc(Replaces an object's own points (a deformer notices through the object's revision).

Args:
    name: the object's name.
    mesh: MeshData.
Raises:
    ValueError: an unknown object.)doc")
      .def("latticesDeforming", py::overload_cast<const std::string&>(&scenes::Scene::latticesDeforming, py::const_), "object"_a, R"doc(The root lattices deforming an object, in attachment order.

Args:
    object: the object's name.
Returns:
    list of WidgetId.)doc")
      .def("validate", &scenes::validateScene, R"doc(Checks the scene: unique names, attachments naming existing root lattices and objects.

Raises:
    SceneFileError: naming what is wrong.)doc");

  m.def("readScene", py::overload_cast<const std::filesystem::path&>(&scenes::readScene), "path"_a,
        py::call_guard<py::gil_scoped_release>(), R"doc(Reads a scene file, or <folder>/scene.json, with its meshes, generators and widget file.

Args:
    path: a .json file or a folder.
Returns:
    Scene. The interpreter lock is released while it reads.
Raises:
    SceneFileError: the file and the JSON pointer of what is wrong. MeshIoError: a mesh file.
    WidgetFileError: its widget file. GeneratorError: a generated object.)doc");
  m.def("writeScene", py::overload_cast<const std::filesystem::path&, const scenes::Scene&>(&scenes::writeScene),
        "path"_a, "scene"_a, py::call_guard<py::gil_scoped_release>(), R"doc(Writes a scene file atomically.

Args:
    path: the .json file (or a folder: <folder>/scene.json).
    scene: Scene.
Raises:
    SceneFileError: the scene cannot be written (the message says why).)doc");
  m.def("sceneFileText", &scenes::sceneFileText, "scene"_a, R"doc(The scene file's JSON text, as writeScene writes it.

Args:
    scene: Scene.
Returns:
    str.)doc");
  m.def("readWidgetFile", py::overload_cast<const std::filesystem::path&>(&scenes::readWidgetFile), "path"_a,
        py::call_guard<py::gil_scoped_release>(), R"doc(Reads a widget file: lattices, cells, affine widgets and bindings (docs/widget-file-format.md).

Args:
    path: the .json file.
Returns:
    WidgetModel. The interpreter lock is released while it reads.
Raises:
    WidgetFileError: the file and the JSON pointer of what is wrong.)doc");
  m.def("writeWidgetFile",
        py::overload_cast<const std::filesystem::path&, const widgets::WidgetModel&>(&scenes::writeWidgetFile), "path"_a,
        "model"_a, py::call_guard<py::gil_scoped_release>(), R"doc(Writes a widget file atomically.

Args:
    path: the .json file.
    model: WidgetModel.
Raises:
    WidgetFileError: the file cannot be written.)doc");
  m.def("widgetFileText", &scenes::widgetFileText, "model"_a, R"doc(The widget file's JSON text, as writeWidgetFile writes it.

Args:
    model: WidgetModel.
Returns:
    str.)doc");

  py::class_<scenes::SceneDeformStats>(m, "SceneDeformStats", R"doc(Timing and work of the last SceneDeformer update.

Fields: seconds, reembeddedStages, deformedPoints, outsidePoints, failedPoints, embedSeconds,
latticesBuilt, deltaStages.)doc")
      .def_readonly("seconds", &scenes::SceneDeformStats::seconds)
      .def_readonly("reembeddedStages", &scenes::SceneDeformStats::reembeddedStages)
      .def_readonly("deformedPoints", &scenes::SceneDeformStats::deformedPoints)
      .def_readonly("outsidePoints", &scenes::SceneDeformStats::outsidePoints)
      .def_readonly("failedPoints", &scenes::SceneDeformStats::failedPoints)
      .def_readonly("embedSeconds", &scenes::SceneDeformStats::embedSeconds)
      .def_readonly("latticesBuilt", &scenes::SceneDeformStats::latticesBuilt)
      .def_readonly("deltaStages", &scenes::SceneDeformStats::deltaStages);

  py::class_<scenes::GestureMotion>(m, "GestureMotion", R"doc(How an object's points moved by delta steps of its last lattice stage since their base revision.

A point's motion is sum_c controlWeights(name, c) * displacements[c]. Fields: baseRevision,
lattice, controlPoints, displacements.)doc")
      .def_readonly("baseRevision", &scenes::GestureMotion::baseRevision)
      .def_readonly("lattice", &scenes::GestureMotion::lattice)
      .def_readonly("controlPoints", &scenes::GestureMotion::controlPoints)
      .def_readonly("displacements", &scenes::GestureMotion::displacements);

  py::class_<SceneDeformerHandle>(m, "SceneDeformer", R"doc(Evaluates a scene's lattice trees per object, re-embedding and re-evaluating only what changed.

Keep one per scene and call update(scene) after every edit; points(name) gives an object's
deformed points (scenes/scene_deformer.h).)doc")
      .def(py::init<>(), R"doc(A deformer with nothing computed yet.

The first update(scene) embeds every object.)doc")
      .def("update",
           [](SceneDeformerHandle& h, const scenes::Scene& scene, std::optional<widgets::WidgetId> active) {
             h.run([&] { h.deformer.update(scene, active); });
           },
           "scene"_a, "activeLattice"_a = py::none(), R"doc(Brings every object's deformed points up to date.

Args:
    scene: Scene.
    activeLattice: WidgetId of the lattice being edited (it re-embeds at once), or None.
Raises:
    LatticeError: a lattice that cannot embed. Cancelled: the progress callback returned False.
    The interpreter lock is released while it runs.)doc")
      .def("updateGesture",
           [](SceneDeformerHandle& h, const scenes::Scene& scene, std::optional<widgets::WidgetId> active) {
             h.run([&] { h.deformer.updateGesture(scene, active); });
           },
           "scene"_a, "activeLattice"_a = py::none(), R"doc(One step of a gesture: as update(), but a lattice whose control points moved is updated by deltas.

Exact to rounding only, until finishGesture() or update().
Args:
    scene: Scene.
    activeLattice: WidgetId of the dragged lattice, or None.
Raises:
    LatticeError, Cancelled: as update().)doc")
      .def("finishGesture", [](SceneDeformerHandle& h, const scenes::Scene& scene) {
        h.run([&] { h.deformer.finishGesture(scene); });
      }, "scene"_a, R"doc(Ends a gesture: evaluates every lattice updated by deltas in full (the exact result).

Args:
    scene: Scene.
Raises:
    LatticeError, Cancelled: as update().)doc")
      .def("evaluate", [](SceneDeformerHandle& h, const scenes::Scene& scene) {
        bool ran = false;
        h.run([&] { ran = h.deformer.evaluate(scene); });
        return ran;
      }, "scene"_a, R"doc(Brings the points up to date with the scene when it changed since the last evaluation.

The one call a script needs: nothing changed, nothing done; between beginGesture() and
endGesture() a step by deltas, otherwise the exact result.
Args:
    scene: Scene.
Returns:
    bool: whether it evaluated.
Raises:
    LatticeError, Cancelled: as update().)doc")
      .def("beginGesture", [](SceneDeformerHandle& h, std::optional<widgets::WidgetId> active) { h.deformer.beginGesture(active); },
           "activeLattice"_a = py::none(), R"doc(A gesture starts: evaluate() steps by deltas until endGesture().

Args:
    activeLattice: WidgetId of the dragged lattice (it re-embeds at once), or None.)doc")
      .def("endGesture", [](SceneDeformerHandle& h) { h.deformer.endGesture(); },
           R"doc(The gesture ends (released or cancelled).

The next evaluate() gives the exact result, also when nothing changed since the last step.)doc")
      .def("revision", [](const SceneDeformerHandle& h, const std::string& object) { return h.deformer.revision(object); },
           "object"_a, R"doc(A number that grows whenever the object's deformed points change.

Args:
    object: the object's name.
Raises:
    ValueError: an unknown object.)doc")
      .def("gestureMotion",
           [](const SceneDeformerHandle& h, const std::string& object) { return h.deformer.gestureMotion(object); },
           "object"_a, R"doc(The object's motion by delta steps of its last lattice stage since its base.

Args:
    object: the object's name.
Returns:
    GestureMotion, or None when its last update was not by deltas.)doc")
      .def("controlWeights",
           [](const SceneDeformerHandle& h, const std::string& object, Eigen::Index controlPoint) {
             return h.deformer.controlWeights(object, controlPoint);
           },
           "object"_a, "controlPoint"_a, R"doc(The weight of one control point of the object's last lattice stage at each of its points.

Args:
    object: the object's name.
    controlPoint: flat index in that lattice.
Returns:
    array of #points weights.
Raises:
    ValueError: an unknown object, one without lattices or not embedded yet.
    LatticeError: a control point out of range.)doc")
      .def("setProgress",
           [](SceneDeformerHandle& h, const py::object& callback) {
             h.progress = PythonProgress(callback);
             h.deformer.setProgress(h.progress.fractionHook());
           },
           "progress"_a, R"doc(Sets the callback that reports progress of long updates and may cancel them.

Args:
    progress: callable(fraction) called on the updating thread; returning False (or raising)
        cancels the update with Cancelled (or that exception); None or True goes on.)doc")
      .def("points",
           [](py::object self, const std::string& object) {
             return viewOf(self.cast<SceneDeformerHandle&>().deformer.points(object), self, false);
           },
           "object"_a, R"doc(An object's deformed points, #points x 3.

Args:
    object: the object's name.
Returns:
    A read-only view that the next update rewrites (.copy() to keep).
Raises:
    ValueError: an unknown object.)doc")
      .def_property_readonly("lastStats", [](const SceneDeformerHandle& h) { return h.deformer.lastStats(); })
      .def("reset", [](SceneDeformerHandle& h) { h.deformer.reset(); }, R"doc(Forgets everything computed; the next update embeds every object again.

Returns:
    None.)doc");

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
        "scene"_a, R"doc(The deformed points of every object of a scene, in one call.

Args:
    scene: Scene.
Returns:
    dict {object name: N x 3 array}. The interpreter lock is released while it runs.
Raises:
    LatticeError: a lattice that cannot embed.)doc");
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
