"""ffdkit scenes in Blender: import a scene's objects with their tools and keys, and write the
sliders' values and keys back to the scene file.

Each object of the scene becomes a mesh object (at the identity: ffdkit scenes hold world
points) carrying the scene's widget model, at its stored frames, deforming it through the root
lattices attached to it; each variation channel of the scene's animation becomes keys on the
slider of its widget (frame = seconds x frames per second; smooth -> Bezier with auto-clamped
handles, linear -> linear, constant -> constant). Lattice-frame and control-point channels have
no slider and are not imported (the import says so). Export writes the objects' current slider
values and their slider keys into the scene (replacing those widgets' variation keys) and saves it.
"""

import json
import os

import numpy as np

from . import mesh_link

SCENE_KEY = "_ffdkit_scene"    # the scene file the object came from
OBJECT_KEY = "_ffdkit_object"  # the object's name in it

_TO_BLENDER = {"smooth": "BEZIER", "linear": "LINEAR", "constant": "CONSTANT"}


def scene_file(path):
    """The scene's JSON file: the path itself, or <folder>/scene.json."""
    return os.path.join(path, "scene.json") if os.path.isdir(path) else path


def variation_channels(path):
    """[(widget, [(seconds, value, interpolation)])] of the scene file's variation channels, and
    the names of its other channels (not imported)."""
    with open(scene_file(path), encoding="utf-8") as source:
        animation = json.load(source).get("animation", {})
    channels, skipped = [], []
    for channel in animation.get("channels", []):
        if channel.get("property") == "variation":
            channels.append((channel["widget"], [(k["time"], k["value"], k.get("interpolation", "smooth"))
                                                 for k in channel["keys"]]))
        else:
            skipped.append("%s (%s)" % (channel.get("widget"), channel.get("property")))
    return channels, skipped


def import_scene(bpy, ffdkit, path, collection):
    """Creates one mesh object per scene object, each with its tool and slider keys.

    Returns:
        (objects, notes): the new objects, and what was not imported.
    Raises:
        ffdkit.Error / OSError / ValueError: the scene cannot be read (ffdkit's message), or a
            tool cannot be attached (tool.ToolError).
    """
    scene = ffdkit.scenes.readScene(path)
    channels, skipped = variation_channels(path)
    text = ffdkit.scenes.widgetFileText(scene.widgets)
    fps = scene.framesPerSecond
    objects, notes = [], []
    if skipped:
        notes.append("not imported (no slider for them): keys of %s" % ", ".join(skipped))
    for name in scene.objectNames():
        mesh_data = scene.findObject(name).mesh
        mesh = _blender_mesh(bpy, name, mesh_data)
        obj = bpy.data.objects.new(name, mesh)
        collection.objects.link(obj)
        roots = [scene.widgets.name(a.lattice) for a in scene.attachments if name in _object_names(scene, a)]
        if not roots:
            notes.append("'%s' has no lattice attached: imported without a tool" % name)
            objects.append(obj)
            continue
        tool = mesh_link.attach(ffdkit, obj, text, path, fit=False, roots=roots)
        obj[SCENE_KEY] = os.path.abspath(path)
        obj[OBJECT_KEY] = name
        for widget, keys in channels:
            if widget not in tool.affine_names():
                continue
            data_path = '["%s%s"]' % (mesh_link.PREFIX, widget)
            for seconds, value, _ in keys:
                obj[mesh_link.PREFIX + widget] = float(value)
                obj.keyframe_insert(data_path, frame=seconds * fps)
            curve = obj.animation_data.action.fcurves.find(data_path)
            _set_handles(curve, keys, fps)
        objects.append(obj)
    return objects, notes


def smooth_slopes(times, values):
    """ffdkit's automatic slopes of smooth keys (docs/animation.md, `autoSlope`): the
    finite-difference slope (p[i+1] - p[i-1]) / (t[i+1] - t[i-1]) at an interior key, 0 at the
    first and last key and at a local extremum."""
    slopes = [0.0] * len(times)
    for i in range(1, len(times) - 1):
        before, after = values[i] - values[i - 1], values[i + 1] - values[i]
        if before * after > 0:
            slopes[i] = (values[i + 1] - values[i - 1]) / (times[i + 1] - times[i - 1])
    return slopes


def _set_handles(curve, keys, fps):
    """Interpolation per key; a smooth segment gets free Bezier handles a third of the way along
    its time span with ffdkit's slopes, so the Bezier is ffdkit's cubic Hermite segment exactly
    (Blender's own automatic handles follow another rule at monotone interior keys)."""
    frames = [seconds * fps for seconds, _, _ in keys]
    values = [value for _, value, _ in keys]
    slopes = smooth_slopes(frames, values)
    points = curve.keyframe_points
    for i, (point, (_, _, interpolation)) in enumerate(zip(points, keys)):
        point.interpolation = _TO_BLENDER.get(interpolation, "BEZIER")
        point.handle_left_type = point.handle_right_type = "FREE"
        if i > 0:
            step = (frames[i] - frames[i - 1]) / 3.0
            point.handle_left = (frames[i] - step, values[i] - slopes[i] * step)
        if i + 1 < len(points):
            step = (frames[i + 1] - frames[i]) / 3.0
            point.handle_right = (frames[i] + step, values[i] + slopes[i] * step)


def _object_names(scene, attachment):
    """The names of the objects an attachment deforms (it holds names or, in newer modules,
    ObjectIds)."""
    return [o if isinstance(o, str) else scene.objectName(o) for o in attachment.objects]


def _blender_mesh(bpy, name, mesh_data):
    points = np.asarray(mesh_data.points, dtype=np.float32)
    triangles = np.asarray(mesh_data.triangles, dtype=np.int32)
    segments = np.asarray(mesh_data.segments, dtype=np.int32)
    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(len(points))
    mesh.vertices.foreach_set("co", points.ravel())
    if len(segments):
        mesh.edges.add(len(segments))
        mesh.edges.foreach_set("vertices", segments.ravel())
    if len(triangles):
        mesh.loops.add(triangles.size)
        mesh.loops.foreach_set("vertex_index", triangles.ravel())
        mesh.polygons.add(len(triangles))
        mesh.polygons.foreach_set("loop_start", np.arange(0, triangles.size, 3, dtype=np.int32))
        mesh.polygons.foreach_set("loop_total", np.full(len(triangles), 3, dtype=np.int32))
    mesh.update(calc_edges=True)
    return mesh


_TO_FFDKIT = {"BEZIER": "Smooth", "LINEAR": "Linear", "CONSTANT": "Constant"}


def export_scene(ffdkit, objects, source, target, fps):
    """Writes the scene at `source` with the objects' slider values and slider keys to `target`.

    Args:
        objects: Blender objects imported from `source` (their tools' sliders are read).
        fps: Blender's frames per second (key frame / fps = seconds).
    Returns:
        Notes on what could not be written (keys of another interpolation are written smooth).
    """
    scene = ffdkit.scenes.readScene(source)
    model = scene.widgets
    Kind = ffdkit.scenes.ChannelKind
    notes = []
    for obj in objects:
        for key in [k for k in obj.keys() if k.startswith(mesh_link.PREFIX)]:
            widget = model.find(key[len(mesh_link.PREFIX):])
            value = float(obj[key])
            if model.variation(widget) != value:
                model.setVariation(widget, value)
            data = obj.animation_data
            curve = data.action.fcurves.find('["%s"]' % key) if data is not None and data.action is not None else None
            if curve is None:
                continue
            for seconds in scene.keyTimes(widget):
                if scene.keyValue(widget, Kind.Variation, seconds) is not None:
                    scene.removeKey(widget, Kind.Variation, seconds)
            notes.extend(_slope_differences(key, curve))
            for point in curve.keyframe_points:
                name = _TO_FFDKIT.get(point.interpolation)
                if name is None:
                    notes.append("%s: %s keys written as smooth" % (key, point.interpolation.lower()))
                    name = "Smooth"
                scene.setKey(widget, Kind.Variation, point.co[0] / fps, float(point.co[1]),
                             getattr(ffdkit.scenes.Interpolation, name))
    ffdkit.scenes.writeScene(target, scene)
    return notes


def _slope_differences(key, curve):
    """Notes for Bezier keys whose handles' slope is not ffdkit's automatic one: ffdkit's smooth
    keys have no handles, so those segments play differently there."""
    points = curve.keyframe_points
    frames = [p.co[0] for p in points]
    slopes = smooth_slopes(frames, [p.co[1] for p in points])
    notes = []
    for point, slope in zip(points, slopes):
        if point.interpolation != "BEZIER":
            continue
        for handle, sign in ((point.handle_right, 1.0), (point.handle_left, -1.0)):
            run = sign * (handle[0] - point.co[0])
            if run > 1e-9 and abs(sign * (handle[1] - point.co[1]) / run - slope) > 1e-4 * max(1e-3, abs(slope)):
                notes.append("%s: the key at frame %g has Bezier handles ffdkit's smooth keys do not have "
                             "(slope %.4g per frame there, %.4g in ffdkit): ffdkit plays it differently"
                             % (key, point.co[0], (handle[1] - point.co[1]) / (handle[0] - point.co[0]), slope))
                break
    return notes
