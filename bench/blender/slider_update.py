"""Times a slider change of the ffdkit add-on on a big mesh inside Blender, beside Blender's own
Lattice modifier on the same mesh.

    FFDKIT_PYTHONPATH=build/python blender -b --factory-startup --python bench/blender/slider_update.py -- [VERTICES] [REPS]

A latitude-longitude sphere of about VERTICES vertices (quads) (default 1,000,000) gets the fig6-8 tool (fitted); each
repetition sets a new value of its 'push-front' slider and times, wall clock, from the change to
the evaluated mesh holding the new positions: the add-on's handler before the evaluation
(ffdkit's update and one foreach_set into the shape key) and Blender's evaluation of the mesh. The same mesh with a
4x4x4 B-spline Lattice modifier instead: a lattice point moves, then the evaluation. Prints the
medians over REPS (default 10), with the handler's share, in ms.
"""

import os
import statistics
import sys
import time

import addon_utils
import bpy
import numpy as np

args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
vertices = int(args[0]) if args else 1_000_000
reps = int(args[1]) if len(args) > 1 else 10
root = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
sys.path.insert(0, os.path.join(root, "blender"))
addon = addon_utils.enable("ffdkit_blender", default_set=True)
addon.ffdkit_module()
from ffdkit_blender import mesh_link  # noqa: E402

for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)


def sphere_mesh(side):
    """A side x side latitude-longitude grid of quads on the unit sphere (poles left open), built
    from numpy arrays (bpy.ops.mesh.primitive_uv_sphere_add takes minutes at this size)."""
    theta, phi = np.meshgrid(np.linspace(0.02, np.pi - 0.02, side), np.linspace(0, 2 * np.pi, side, endpoint=False),
                             indexing="ij")
    points = np.stack([np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)], axis=-1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(side - 1), np.arange(side), indexing="ij")
    quads = np.stack([i * side + j, i * side + (j + 1) % side, (i + 1) * side + (j + 1) % side, (i + 1) * side + j],
                     axis=-1).reshape(-1, 4)
    mesh = bpy.data.meshes.new("sphere")
    mesh.vertices.add(len(points))
    mesh.vertices.foreach_set("co", points.astype(np.float32).ravel())
    mesh.loops.add(quads.size)
    mesh.loops.foreach_set("vertex_index", quads.astype(np.int32).ravel())
    mesh.polygons.add(len(quads))
    mesh.polygons.foreach_set("loop_start", np.arange(0, quads.size, 4, dtype=np.int32))
    mesh.polygons.foreach_set("loop_total", np.full(len(quads), 4, dtype=np.int32))
    mesh.update(calc_edges=True)
    mesh.validate()
    obj = bpy.data.objects.new("sphere", mesh)
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    return obj


sphere = sphere_mesh(max(3, int(round(np.sqrt(vertices)))))
count = len(sphere.data.vertices)
view_layer = bpy.context.view_layer


def evaluated_points(obj):
    mesh = obj.evaluated_get(bpy.context.evaluated_depsgraph_get()).data
    flat = np.empty(3 * len(mesh.vertices), dtype=np.float32)
    mesh.vertices.foreach_get("co", flat)
    return flat


# ---- the add-on's slider ------------------------------------------------------------------
tool = os.path.join(root, "widgets", "examples", "fig6-8.json")
start = time.perf_counter()
assert bpy.ops.ffdkit.load_tool(filepath=tool, fit=True) == {"FINISHED"}
view_layer.update()
load_ms = 1e3 * (time.perf_counter() - start)
handler_ms = []
original_write = mesh_link.write


def timed_write(obj, link):
    t = time.perf_counter()
    original_write(obj, link)
    handler_ms.append(1e3 * (time.perf_counter() - t))


mesh_link.write = timed_write
slider = []
for k in range(reps):
    before = evaluated_points(sphere)
    t = time.perf_counter()
    sphere["ffd:push-front"] = 0.02 * (k + 1)
    sphere.update_tag()  # a scripted change; in the interface the add-on's poll notices it within 50 ms
    view_layer.update()  # the add-on's pre-evaluation handler writes the key; Blender evaluates the mesh
    slider.append(1e3 * (time.perf_counter() - t))
    assert np.abs(evaluated_points(sphere) - before).max() > 1e-3, "the slider did not move the mesh"
mesh_link.write = original_write

# The handler's parts: ffdkit's update after a slider change, the float32 copy, the foreach_set.
link = mesh_link.link_of(addon.ffdkit_module(), sphere)
update_ms, copy_ms, set_ms = [], [], []
block = sphere.data.shape_keys.key_blocks[mesh_link.SHAPE_KEY]
for k in range(reps):
    link.tool.set_variations({"push-front": 0.01 * (k + 1)})
    t = time.perf_counter()
    points = link.tool.points()
    update_ms.append(1e3 * (time.perf_counter() - t))
    t = time.perf_counter()
    flat = np.ascontiguousarray(points, dtype=np.float32).ravel()
    copy_ms.append(1e3 * (time.perf_counter() - t))
    t = time.perf_counter()
    block.data.foreach_set("co", flat)
    set_ms.append(1e3 * (time.perf_counter() - t))

# ---- Blender's Lattice modifier on the same mesh --------------------------------------------
assert bpy.ops.ffdkit.remove_tool() == {"FINISHED"}
data = bpy.data.lattices.new("cage")
data.points_u = data.points_v = data.points_w = 4
data.interpolation_type_u = data.interpolation_type_v = data.interpolation_type_w = "KEY_BSPLINE"
cage = bpy.data.objects.new("cage", data)
bpy.context.scene.collection.objects.link(cage)
cage.scale = (2.2 / 3, 2.2 / 3, 2.2 / 3)
modifier = sphere.modifiers.new("cage", "LATTICE")
modifier.object = cage
view_layer.update()
lattice = []
for k in range(reps):
    before = evaluated_points(sphere)
    t = time.perf_counter()
    point = data.points[21]
    point.co_deform = (point.co[0] + 0.05 * (k + 1), point.co[1], point.co[2])
    data.update_tag()
    view_layer.update()
    lattice.append(1e3 * (time.perf_counter() - t))
    assert np.abs(evaluated_points(sphere) - before).max() > 1e-3, "the lattice point did not move the mesh"

print("blender_slider_bench vertices %d, tool fig6-8 (fitted), median of %d" % (count, reps))
print("  load tool (embed + first write):      %8.1f ms" % load_ms)
print("  ffdkit slider -> evaluated mesh:      %8.1f ms  (handler: ffdkit update + foreach_set %.1f ms)"
      % (statistics.median(slider), statistics.median(handler_ms)))
print("    ffdkit update %.1f ms, float32 copy %.1f ms, foreach_set into the shape key %.1f ms"
      % (statistics.median(update_ms), statistics.median(copy_ms), statistics.median(set_ms)))
print("  Blender Lattice modifier 4x4x4 B-spline, point move -> evaluated mesh: %8.1f ms" % statistics.median(lattice))
