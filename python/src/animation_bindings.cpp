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
#include "scene_binding_support.h"
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
            s.addObject(meshFileObject(name, path, up));
          },
          "name"_a, "path"_a, "up"_a = "z", R"doc(Adds an object read from a mesh file.

Args:
    name: the new object's unique name.
    path: the mesh file (kept for the scene file, relative to the working folder here).
    up: "z" (default) or "y": a Y-up file is turned upright as it is read.
Raises:
    ValueError: up is neither, or the name is empty or taken. MeshIoError: the file cannot be read.)doc")
      .def("removeObject", &Scene::removeObject, "name"_a, R"doc(Removes an object and its place in every attachment.

Args:
    name: the object's name.
Raises:
    ValueError: an unknown object.)doc")
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
          "objects"_a, "name"_a = "", "counts"_a = Eigen::Vector3i::Constant(3), "padding"_a = 0.05, R"doc(Adds a root lattice fitted around objects and attaches it to them (Kuriyama 1996, sec. 6.4).

Args:
    objects: the objects' names.
    name: the lattice's name; "" -> "lattice<N>".
    counts: control points per axis (default 3, 3, 3).
    padding: margin on every side, relative to the objects' bounding-box diagonal.
Returns:
    WidgetId of the new lattice.
Raises:
    ValueError: an unknown object or none given. WidgetError: bad counts or a duplicate name.)doc")
      .def("detachLattice", py::overload_cast<widgets::WidgetId, const std::string&>(&Scene::detach), "lattice"_a, "object"_a, R"doc(Stops a lattice deforming an object (an attachment left with no object goes).

Args:
    lattice: WidgetId of the root lattice.
    object: the object's name.
Raises:
    ValueError: the lattice was not attached to the object.)doc")
      .def(
          "detachLattice",
          [](Scene& s, const std::string& lattice, const std::string& object) {
            s.detach(s.widgets.find(lattice), object);
          },
          "lattice"_a, "object"_a, R"doc(Stops a lattice, given by its name, deforming an object.

Args:
    lattice: the root lattice's name.
    object: the object's name.
Raises:
    WidgetError: an unknown lattice. ValueError: it was not attached to the object.)doc")
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
          "widget"_a, "kind"_a, "seconds"_a, "value"_a, "interpolation"_a = Interpolation::Smooth, R"doc(Keys a widget's property at a time (docs/animation.md).

Args:
    widget: WidgetId.
    kind: ChannelKind: Variation (value a float), LatticeFrame (a 4 x 4 frame) or ControlPoints
        (N x 3 local control points).
    seconds: the key's time.
    value: the keyed value, as the kind says.
    interpolation: Interpolation of the segment to the next key (default Smooth).
Returns:
    The value of the key it replaced, or None.
Raises:
    AnimationError: a kind the widget cannot key, a value of the wrong shape, a time out of range.)doc")
      .def(
          "keyCurrent",
          [](Scene& s, WidgetId widget, ChannelKind kind, double seconds, Interpolation interpolation) {
            scenes::setKey(s, widget, kind, scenes::currentKey(s, widget, kind, seconds, interpolation));
          },
          "widget"_a, "kind"_a, "seconds"_a, "interpolation"_a = Interpolation::Smooth, R"doc(Keys the widget's present value (as Insert Key in the app).

Args:
    widget: WidgetId.
    kind: ChannelKind.
    seconds: the key's time.
    interpolation: Interpolation (default Smooth).
Raises:
    AnimationError: a kind the widget cannot key, a time out of range.)doc")
      .def(
          "removeKey",
          [](Scene& s, WidgetId widget, ChannelKind kind, double seconds) {
            const std::optional<Keyframe> removed = scenes::removeKey(s, widget, kind, seconds);
            return removed ? valueOf(kind, *removed) : py::none();
          },
          "widget"_a, "kind"_a, "seconds"_a, R"doc(Removes the key at a time.

Args:
    widget: WidgetId.
    kind: ChannelKind.
    seconds: the key's time.
Returns:
    The removed key's value, or None when there was none.)doc")
      .def(
          "keyValue",
          [](const Scene& s, WidgetId widget, ChannelKind kind, double seconds) {
            const std::optional<Keyframe> key = scenes::keyAt(s.animation(), widget, kind, seconds);
            return key ? valueOf(kind, *key) : py::none();
          },
          "widget"_a, "kind"_a, "seconds"_a, R"doc(The value of the key at a time.

Args:
    widget: WidgetId.
    kind: ChannelKind.
    seconds: the key's time.
Returns:
    The value (a float, a 4 x 4 frame or N x 3 control points), or None when there is no key.)doc")
      .def(
          "keyTimes",
          [](const Scene& s, std::optional<WidgetId> widget) {
            return widget ? scenes::keyTimes(s, *widget) : scenes::keyTimes(s);
          },
          "widget"_a = py::none(), R"doc(The key times in seconds, sorted and unique.

Args:
    widget: a WidgetId for its keys only, or None for every key.
Returns:
    list of float.)doc")
      .def("keyableKinds", [](const Scene& s, WidgetId widget) { return scenes::keyableKinds(s.widgets, widget); },
           "widget"_a, R"doc(The properties of a widget that can be keyed.

Args:
    widget: WidgetId.
Returns:
    list of ChannelKind (an affine widget: Variation; a lattice: LatticeFrame, ControlPoints).)doc")
      .def("applyAnimation", &scenes::applyAnimation, "seconds"_a, R"doc(Sets the widget model to the animation at a time, through its own gestures (bindings follow).

Args:
    seconds: the time.
Raises:
    AnimationError: a non-finite time, or during a gesture. WidgetError: from the model.
    Re-deform with a SceneDeformer afterwards.)doc")
      .def("applyAnimationFrame", &scenes::applyAnimationFrame, "frame"_a, R"doc(Sets the widget model to the animation at a frame (frame / framesPerSecond seconds).

Args:
    frame: the frame number.
Raises:
    AnimationError: as applyAnimation().)doc")
      .def("frameTime", [](const Scene& s, double frame) { return scenes::frameTime(s.animation(), frame); }, "frame"_a, R"doc(The time of a frame, in seconds.

Args:
    frame: the frame number (may be fractional).
Returns:
    frame / framesPerSecond.)doc")
      .def("validateAnimation", &scenes::validateAnimation, R"doc(Checks the animation: frame rate and range, channels naming existing widgets, key counts and values.

Raises:
    AnimationError: naming what is wrong.)doc");
}

void bindAnimationTypes(py::module_& m) {
  py::enum_<Interpolation>(m, "Interpolation", R"doc(How a key's segment to the next key is interpolated.

Constant (a step), Linear (straight to the next key; frames slerp), or Smooth (the default:
cubic Hermite with automatic clamped slopes, through every key, no overshoot).)doc")
      .value("Constant", Interpolation::Constant)
      .value("Linear", Interpolation::Linear)
      .value("Smooth", Interpolation::Smooth);
  py::enum_<ChannelKind>(m, "ChannelKind", R"doc(What a channel keys.

Variation (of an affine widget), LatticeFrame (a lattice's world frame) or ControlPoints (a
lattice's local control points).)doc")
      .value("Variation", ChannelKind::Variation)
      .value("LatticeFrame", ChannelKind::LatticeFrame)
      .value("ControlPoints", ChannelKind::ControlPoints);
}

}  // namespace ffdkit::python
