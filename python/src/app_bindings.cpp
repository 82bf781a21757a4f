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
#include "ffdkit/app/interaction_controller.h"
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
  py::class_<Document>(m, "Document",
                       "A scene edited as the app edits it: each operation one undoable command (only "
                       "what changed is kept), the objects re-deformed after each (docs/python.md).")
      .def(py::init<scenes::Scene>(), "scene"_a = scenes::Scene(), "Takes a copy of `scene`.")
      .def_property_readonly("scene", &Document::scene, py::return_value_policy::reference_internal,
                             "The document's scene: read it freely; edit it through the Document, or "
                             "undo loses track.")
      .def(
          "points",
          [](const Document& d, const std::string& object) {
            return toArray(Eigen::MatrixX3d(d.deformer().points(object)));
          },
          "object"_a, "The object's deformed points (a copy).")
      // ---- operations: one command each ----
      .def(
          "newLattice",
          [](Document& d, const Eigen::Vector3i& counts, bool cylindrical) {
            app::NewLatticeOptions options;
            options.counts = counts;
            options.cylindrical = cylindrical;
            return d.controller().newLattice(options);
          },
          "counts"_a = Eigen::Vector3i::Constant(3), "cylindrical"_a = false,
          "A new root lattice (a unit box at the origin, Bernstein bases); returns its WidgetId.")
      .def(
          "addMeshFile",
          [](Document& d, const std::string& name, const std::string& path, const std::string& up) {
            if (up != "z" && up != "y") throw py::value_error("up must be 'z' or 'y', got '" + up + "'");
            scenes::SceneObject object;
            object.name = name;
            object.source = scenes::MeshFileSource{path, up == "y" ? scenes::UpAxis::Y : scenes::UpAxis::Z};
            object.mesh = scenes::buildObjectMesh(object.source, ".");
            d.controller().addObject(std::move(object));
          },
          "name"_a, "path"_a, "up"_a = "z", "Adds an object read from a mesh file.")
      .def("attachLattice", [](Document& d, WidgetId lattice, const std::string& object) {
             d.controller().attachLattice(lattice, object);
           }, "lattice"_a, "object"_a, "Fits a root lattice around the object and attaches it.")
      .def("detachLattice", [](Document& d, WidgetId lattice, const std::string& object) {
             d.controller().detachLattice(lattice, object);
           }, "lattice"_a, "object"_a)
      .def("addCell", [](Document& d, WidgetId lattice, const widgets::CellSpec& spec) {
             return d.controller().addCell(lattice, spec);
           }, "lattice"_a, "spec"_a)
      .def("addAffine", [](Document& d, WidgetId cell, widgets::AffineKind kind) {
             return d.controller().addAffine(cell, kind);
           }, "cell"_a, "kind"_a)
      .def("bind", [](Document& d, WidgetId a, WidgetId b) { return d.controller().bind(a, b); }, "a"_a, "b"_a,
           "Binds two widgets; the kind follows from their types.")
      .def("setVariation", [](Document& d, WidgetId affine, double value) { d.controller().setVariation(affine, value); },
           "affine"_a, "value"_a, "Consecutive changes of one widget's variation merge into one undo step.")
      .def("setLatticeFrame", [](Document& d, WidgetId lattice, const py::object& frame) {
             d.controller().setLatticeFrame(lattice, affineArg(frame, "frame"));
           }, "lattice"_a, "frame"_a)
      .def("setLatticeCounts", [](Document& d, WidgetId lattice, const Eigen::Vector3i& counts) {
             d.controller().setLatticeCounts(lattice, counts);
           }, "lattice"_a, "counts"_a)
      .def("removeWidget", [](Document& d, WidgetId id) { d.controller().removeWidget(id); }, "widget"_a)
      .def("renameWidget", [](Document& d, WidgetId id, const std::string& name) { d.controller().renameWidget(id, name); },
           "widget"_a, "name"_a)
      .def("removeObjects", [](Document& d, const std::vector<std::string>& names) { d.controller().removeObjects(names); },
           "objects"_a)
      .def("renameObject", [](Document& d, const std::string& object, const std::string& name) {
             d.controller().renameObject(object, name);
           }, "object"_a, "name"_a)
      // ---- history ----
      .def("undo", [](Document& d) {
             if (!d.commands().canUndo()) throw py::value_error("nothing to undo");
             d.commands().undo();
           })
      .def("redo", [](Document& d) {
             if (!d.commands().canRedo()) throw py::value_error("nothing to redo");
             d.commands().redo();
           })
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
