// ffdkit.app: a scene edited the way the application edits it, through the interaction
// controller (app/interaction, no Qt, no VTK): every operation one undoable command holding only
// what it changed, the objects re-deformed after each, undo and redo.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "numpy_eigen.h"
#include "scene_binding_support.h"
#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/scenes/command_stack.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_deformer.h"

namespace ffdkit::python {

using namespace pybind11::literals;
using widgets::WidgetId;

namespace {

/// A scene with its deformer, undo stack and controller, as one window of the app holds them.
/// The controller keeps references to the other three, so they live here, in place.
class Document {
 public:
  explicit Document(scenes::Scene scene) : scene_(std::move(scene)), controller_(scene_, deformer_, commands_) {
    controller_.refresh();  // the objects deformed as they are
  }
  scenes::Scene& scene() { return scene_; }
  app::InteractionController& controller() { return controller_; }
  scenes::CommandStack& commands() { return commands_; }
  const scenes::SceneDeformer& deformer() const { return deformer_; }

 private:
  scenes::Scene scene_;
  scenes::SceneDeformer deformer_;
  scenes::CommandStack commands_;
  app::InteractionController controller_;
};

}  // namespace

void bindApp(py::module_& m) {
  using app::InteractionController;
  py::class_<Document>(m, "Document", R"doc(A scene edited as the app edits it: each operation is one undoable command, the objects re-deformed after each.

Document(scene) takes a copy; edit it through the methods below (the same controller the window
uses), read it through .scene and points(name), and step through history with undo() / redo().
A failing operation raises WidgetError or ValueError and changes nothing.)doc")
      .def(py::init<scenes::Scene>(), "scene"_a = scenes::Scene(), R"doc(A document holding a copy of a scene, its objects deformed.

Args:
    scene: Scene (default: an empty scene).)doc")
      .def_property_readonly("scene", &Document::scene, py::return_value_policy::reference_internal,
                             "The document's scene: read it freely; edit it through the Document, or "
                             "undo loses track.")
      .def(
          "points",
          [](const Document& d, const std::string& object) {
            return toArray(Eigen::MatrixX3d(d.deformer().points(object)));
          },
          "object"_a, R"doc(An object's deformed points, #points x 3 (a copy).

Args:
    object: the object's name.
Raises:
    ValueError: an unknown object.)doc")
      // ---- operations: one command each ----
      .def(
          "newLattice",
          [](Document& d, const Eigen::Vector3i& counts, bool cylindrical) {
            app::NewLatticeOptions options;
            options.counts = counts;
            options.cylindrical = cylindrical;
            return d.controller().newLattice(options);
          },
          "counts"_a = Eigen::Vector3i::Constant(3), "cylindrical"_a = false, R"doc(Adds a root lattice: a unit box at the origin with Bernstein bases (one undo step).

Args:
    counts: control points per axis (default 3, 3, 3).
    cylindrical: a cylindrical (EFFD) lattice instead of a box.
Returns:
    WidgetId.
Raises:
    WidgetError: counts < 2.)doc")
      .def(
          "addMeshFile",
          [](Document& d, const std::string& name, const std::string& path, const std::string& up) {
            d.controller().addObject(meshFileObject(name, path, up));
          },
          "name"_a, "path"_a, "up"_a = "z", R"doc(Adds an object read from a mesh file (one undo step).

Args:
    name: the new object's unique name.
    path: the mesh file.
    up: "z" (default) or "y" (a Y-up file is turned upright).
Raises:
    ValueError: up is neither, or the name is taken. MeshIoError: the file cannot be read.)doc")
      .def("attachLattice", [](Document& d, WidgetId lattice, const std::string& object) {
             d.controller().attachLattice(lattice, object);
           }, "lattice"_a, "object"_a, R"doc(Fits a root lattice around an object and attaches it (one undo step).

Args:
    lattice: WidgetId of a root lattice.
    object: the object's name.
Raises:
    WidgetError or ValueError: not a root lattice, an unknown object, already attached.)doc")
      .def("detachLattice", [](Document& d, WidgetId lattice, const std::string& object) {
             d.controller().detachLattice(lattice, object);
           }, "lattice"_a, "object"_a, R"doc(Stops a lattice deforming an object (one undo step).

Args:
    lattice: WidgetId of the root lattice.
    object: the object's name.
Raises:
    ValueError: it was not attached.)doc")
      .def("addCell", [](Document& d, WidgetId lattice, const widgets::CellSpec& spec) {
             return d.controller().addCell(lattice, spec);
           }, "lattice"_a, "spec"_a, R"doc(Adds a cell to a lattice (one undo step).

Args:
    lattice: WidgetId.
    spec: CellSpec.
Returns:
    WidgetId.
Raises:
    WidgetError: an unknown lattice or a spec outside its grid.)doc")
      .def("addAffine", [](Document& d, WidgetId cell, widgets::AffineKind kind) {
             return d.controller().addAffine(cell, kind);
           }, "cell"_a, "kind"_a, R"doc(Adds an affine widget on a cell (one undo step).

Args:
    cell: WidgetId.
    kind: AffineKind.
Returns:
    WidgetId.
Raises:
    WidgetError: not a cell.)doc")
      .def("bind", [](Document& d, WidgetId a, WidgetId b) { return d.controller().bind(a, b); }, "a"_a, "b"_a, R"doc(Binds two widgets; the kind follows from their types (one undo step).

Args:
    a, b: WidgetIds.
Returns:
    BindingId.
Raises:
    WidgetError: as WidgetModel.bind.)doc")
      .def("setVariation", [](Document& d, WidgetId affine, double value) { d.controller().setVariation(affine, value); },
           "affine"_a, "value"_a, R"doc(Sets an affine widget's variation; bindings follow. Consecutive changes of one widget merge into one undo step.

Args:
    affine: WidgetId.
    value: the new variation (distance, radians or log scale).
Raises:
    WidgetError: not an affine widget.)doc")
      .def("setLatticeFrame", [](Document& d, WidgetId lattice, const py::object& frame) {
             d.controller().setLatticeFrame(lattice, affineArg(frame, "frame"));
           }, "lattice"_a, "frame"_a, R"doc(Sets a root lattice's world frame (one undo step).

Args:
    lattice: WidgetId.
    frame: 4 x 4 affine matrix.
Raises:
    WidgetError: not a root lattice, a singular frame. ValueError: not 4 x 4.)doc")
      .def("setLatticeCounts", [](Document& d, WidgetId lattice, const Eigen::Vector3i& counts) {
             d.controller().setLatticeCounts(lattice, counts);
           }, "lattice"_a, "counts"_a, R"doc(Changes a lattice's point counts, keeping its deformation as well as it can (one undo step).

Args:
    lattice: WidgetId.
    counts: (l, m, n), each >= 2.
Raises:
    WidgetError: as WidgetModel.setLatticeCounts.)doc")
      .def("removeWidget", [](Document& d, WidgetId id) { d.controller().removeWidget(id); }, "widget"_a, R"doc(Removes a widget with its bindings (one undo step).

Args:
    widget: WidgetId.
Raises:
    WidgetError: an unknown widget.)doc")
      .def("renameWidget", [](Document& d, WidgetId id, const std::string& name) { d.controller().renameWidget(id, name); },
           "widget"_a, "name"_a, R"doc(Renames a widget (one undo step).

Args:
    widget: WidgetId.
    name: the new unique name.
Raises:
    WidgetError: an empty or duplicate name.)doc")
      .def("removeObjects", [](Document& d, const std::vector<std::string>& names) { d.controller().removeObjects(names); },
           "objects"_a, R"doc(Removes objects and their places in the attachments (one undo step).

Args:
    objects: the objects' names.
Raises:
    ValueError: an unknown object.)doc")
      .def("renameObject", [](Document& d, const std::string& object, const std::string& name) {
             d.controller().renameObject(object, name);
           }, "object"_a, "name"_a, R"doc(Renames an object; the attachments follow (one undo step).

Args:
    object: its name.
    name: the new unique name.
Raises:
    ValueError: an unknown object, or an empty or used name.)doc")
      // ---- history ----
      .def("undo", [](Document& d) {
             if (!d.commands().canUndo()) throw py::value_error("nothing to undo");
             d.commands().undo();
           }, R"doc(Undoes the last command.

Raises:
    ValueError: nothing to undo.)doc")
      .def("redo", [](Document& d) {
             if (!d.commands().canRedo()) throw py::value_error("nothing to redo");
             d.commands().redo();
           }, R"doc(Redoes the last undone command.

Raises:
    ValueError: nothing to redo.)doc")
      .def_property_readonly("canUndo", [](Document& d) { return d.commands().canUndo(); })
      .def_property_readonly("canRedo", [](Document& d) { return d.commands().canRedo(); })
      .def_property_readonly("undoDescription", [](Document& d) { return d.commands().undoDescription(); })
      .def_property_readonly("redoDescription", [](Document& d) { return d.commands().redoDescription(); })
      .def_property_readonly("undoSteps", [](Document& d) { return d.commands().size(); },
                             "Commands held (undone ones included, until the next edit drops them).")
      .def_property_readonly("undoBytes", [](Document& d) { return d.commands().bytes(); },
                             "Memory the history holds (deltas, not copies of the document).");
}

}  // namespace ffdkit::python
