// ffdkit.scenes, continued: a scene's objects and lattices edited from Python (scene_changes.h,
// scene.h), and its keyframed animation (keyframes.h, animation.h).
#include <optional>
#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "numpy_eigen.h"
#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_changes.h"

namespace ffdkit::python {

using namespace pybind11::literals;
using scenes::ChannelKind;
using scenes::Interpolation;
using scenes::Keyframe;
using scenes::Scene;
using widgets::WidgetId;

namespace {

// The key `kind` needs, from the one value argument that kind takes.
Keyframe keyOf(ChannelKind kind, double seconds, const py::object& value, Interpolation interpolation) {
  Keyframe key;
  key.time = seconds;
  key.interpolation = interpolation;
  switch (kind) {
    case ChannelKind::Variation: key.variation = value.cast<double>(); break;
    case ChannelKind::LatticeFrame: key.frame = affineArg(value, "value (a 4x4 frame)"); break;
    case ChannelKind::ControlPoints: key.points = PointsArg(value, "value (control points)").ref(); break;
  }
  return key;
}

py::object valueOf(ChannelKind kind, const Keyframe& key) {
  switch (kind) {
    case ChannelKind::Variation: return py::float_(key.variation);
    case ChannelKind::LatticeFrame: return affineToArray(key.frame);
    case ChannelKind::ControlPoints: return toArray(Eigen::MatrixX3d(key.points));
  }
  return py::none();
}

}  // namespace

void bindSceneEditing(py::module_& m) {
  auto scene = py::reinterpret_borrow<py::class_<Scene>>(m.attr("Scene"));
  scene
      .def(
          "addMeshFile",
          [](Scene& s, const std::string& name, const std::string& path, const std::string& up) {
            if (up != "z" && up != "y") throw py::value_error("up must be 'z' or 'y', got '" + up + "'");
            scenes::SceneObject object;
            object.name = name;
            object.source = scenes::MeshFileSource{path, up == "y" ? scenes::UpAxis::Y : scenes::UpAxis::Z};
            {
              py::gil_scoped_release release;
              object.mesh = scenes::buildObjectMesh(object.source, ".");
            }
            s.addObject(std::move(object));
          },
          "name"_a, "path"_a, "up"_a = "z",
          "Adds an object read from a mesh file (the path is kept for the scene file, relative to the "
          "working folder here); up='y' turns a Y-up file upright as it is read.")
      .def("removeObject", &Scene::removeObject, "name"_a,
           "Removes an object and its place in every attachment.")
      .def(
          "attachNewLattice",
          [](Scene& s, const std::vector<std::string>& objects, const std::string& name,
             const Eigen::Vector3i& counts, double padding) {
            scenes::AttachOptions options;
            options.latticeName = name;
            options.counts = counts;
            options.padding = padding;
            return scenes::attachNewLattice(s, objects, options);
          },
          "objects"_a, "name"_a = "", "counts"_a = Eigen::Vector3i::Constant(3), "padding"_a = 0.05,
          "Adds a root lattice fitted around the objects (padded by `padding` of their diagonal) and "
          "attaches it to them; returns its WidgetId.")
      .def("detachLattice", &Scene::detach, "lattice"_a, "object"_a)
      .def(
          "detachLattice",
          [](Scene& s, const std::string& lattice, const std::string& object) {
            s.detach(s.widgets.find(lattice), object);
          },
          "lattice"_a, "object"_a, "The same, the lattice given by its name.")
      // ---- animation ----
      .def_property(
          "framesPerSecond", [](const Scene& s) { return s.animation().framesPerSecond; },
          [](Scene& s, double fps) {
            Scene trial;
            trial.setFrameRate(fps);
            scenes::validateAnimation(trial);  // the range check's message, before anything changes
            s.setFrameRate(fps);
          })
      .def_property(
          "frameRange", [](const Scene& s) { return std::make_pair(s.animation().firstFrame, s.animation().lastFrame); },
          [](Scene& s, std::pair<int, int> range) {
            if (range.first > range.second)
              throw py::value_error("frameRange: first frame " + std::to_string(range.first) + " is after the last " +
                                    std::to_string(range.second));
            s.setFrameRange(range.first, range.second);
          },
          "(first, last) frame of the animation.")
      .def(
          "setKey",
          [](Scene& s, WidgetId widget, ChannelKind kind, double seconds, const py::object& value,
             Interpolation interpolation) {
            const std::optional<Keyframe> replaced =
                scenes::setKey(s, widget, kind, keyOf(kind, seconds, value, interpolation));
            return replaced ? valueOf(kind, *replaced) : py::none();
          },
          "widget"_a, "kind"_a, "seconds"_a, "value"_a, "interpolation"_a = Interpolation::Smooth,
          "Keys `widget` at `seconds`: a variation (float), a lattice frame (4x4) or control points "
          "(N x 3, local). Returns the value of the key it replaced, or None.")
      .def(
          "keyCurrent",
          [](Scene& s, WidgetId widget, ChannelKind kind, double seconds, Interpolation interpolation) {
            scenes::setKey(s, widget, kind, scenes::currentKey(s, widget, kind, seconds, interpolation));
          },
          "widget"_a, "kind"_a, "seconds"_a, "interpolation"_a = Interpolation::Smooth,
          "Keys the widget's present value (as Insert Key in the app).")
      .def(
          "removeKey",
          [](Scene& s, WidgetId widget, ChannelKind kind, double seconds) {
            const std::optional<Keyframe> removed = scenes::removeKey(s, widget, kind, seconds);
            return removed ? valueOf(kind, *removed) : py::none();
          },
          "widget"_a, "kind"_a, "seconds"_a, "Removes the key at `seconds`; returns its value, or None.")
      .def(
          "keyValue",
          [](const Scene& s, WidgetId widget, ChannelKind kind, double seconds) {
            const std::optional<Keyframe> key = scenes::keyAt(s.animation(), widget, kind, seconds);
            return key ? valueOf(kind, *key) : py::none();
          },
          "widget"_a, "kind"_a, "seconds"_a)
      .def(
          "keyTimes",
          [](const Scene& s, std::optional<WidgetId> widget) {
            return widget ? scenes::keyTimes(s, *widget) : scenes::keyTimes(s);
          },
          "widget"_a = py::none(), "Key times in seconds, sorted, unique (of one widget, or of all).")
      .def("keyableKinds", [](const Scene& s, WidgetId widget) { return scenes::keyableKinds(s.widgets, widget); },
           "widget"_a)
      .def("applyAnimation", &scenes::applyAnimation, "seconds"_a,
           "Sets the widget model to the animation at `seconds` through its own gestures (bindings "
           "propagate as in a drag; docs/animation.md). Re-deform with a SceneDeformer afterwards.")
      .def("applyAnimationFrame", &scenes::applyAnimationFrame, "frame"_a)
      .def("frameTime", [](const Scene& s, double frame) { return scenes::frameTime(s.animation(), frame); }, "frame"_a)
      .def("validateAnimation", &scenes::validateAnimation);
}

void bindAnimationTypes(py::module_& m) {
  py::enum_<Interpolation>(m, "Interpolation", "How a key's segment to the next key is interpolated.")
      .value("Constant", Interpolation::Constant)
      .value("Linear", Interpolation::Linear)
      .value("Smooth", Interpolation::Smooth);
  py::enum_<ChannelKind>(m, "ChannelKind", "What a channel keys.")
      .value("Variation", ChannelKind::Variation)
      .value("LatticeFrame", ChannelKind::LatticeFrame)
      .value("ControlPoints", ChannelKind::ControlPoints);
}

}  // namespace ffdkit::python
