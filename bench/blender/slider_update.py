"""Times a slider change of the ffdkit add-on on a big mesh inside Blender, beside Blender's own
Lattice modifier on the same mesh and beside Blender's evaluation of the bare mesh.

    FFDKIT_PYTHONPATH=build/python blender -b --factory-startup --python bench/blender/slider_update.py -- [VERTICES] [REPS]

A latitude-longitude sphere of about VERTICES vertices (quads) (default 1,000,000) gets the
fig6-8 tool (fitted). Each repetition sets a new value of its 'push-front' slider, runs the
add-on's update as its handlers and poll do (apply the sliders to ffdkit's widget model, ffdkit's
update, the write into the shape key, the tag), and evaluates the view layer; it times, wall
clock, from the change to the evaluated mesh holding the new positions, and each part. Then:
- the same mesh with nothing on it, only tagged for a geometry update: Blender's own floor, what
  any change of the mesh costs before anything is deformed;
- two other ways to the evaluated mesh: the key written and the mesh tagged (instead of the Key),
  and no shape key at all, the mesh's own vertices written;
- the same mesh with a 4x4x4 B-spline Lattice modifier instead of the tool: a lattice point
  moves, then the evaluation.
Prints the medians over REPS (default 10), in ms. Drawing is not included (no window: -b).
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
ffdkit = addon.ffdkit_module()
from ffdkit_blender import key_write, mesh_link  # noqa: E402

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


def ms(start):
    return 1e3 * (time.perf_counter() - start)


# Blender's floor: a second sphere with nothing on it, tagged and re-evaluated between the
# slider changes (interleaved, so that both see the same machine).
bare = sphere_mesh(max(3, int(round(np.sqrt(vertices)))))
bpy.context.view_layer.objects.active = sphere
view_layer.update()
floor = []

# ---- the add-on's slider -------------------------------------------------------------------
tool = os.path.join(root, "widgets", "examples", "fig6-8.json")
start = time.perf_counter()
assert bpy.ops.ffdkit.load_tool(filepath=tool, fit=True) == {"FINISHED"}
view_layer.update()
load_ms = ms(start)
link = mesh_link.link_of(ffdkit, sphere)
block = sphere.data.shape_keys.key_blocks[mesh_link.SHAPE_KEY]
total, sync_ms, update_ms, write_ms, evaluate_ms = [], [], [], [], []
original_points = link.tool.points


def timed_points():
    t = time.perf_counter()
    points = original_points()
    update_ms.append(ms(t))
    return points


original_write_points = key_write.write_points


def timed_write_points(*arguments, **options):
    t = time.perf_counter()
    path = original_write_points(*arguments, **options)
    write_ms.append(ms(t))
    return path


link.tool.points = timed_points
key_write.write_points = timed_write_points
for k in range(reps):
    t = time.perf_counter()
    bare.update_tag()
    view_layer.update()
    floor.append(ms(t))
    before = evaluated_points(sphere)
    t = time.perf_counter()
    sphere["ffd:push-front"] = 0.02 * (k + 1)
    # What the add-on's poll (a slider dragged in the interface) or its depsgraph_update_pre
    # handler (a scripted or animated change) runs; the next evaluation picks the write up.
    assert mesh_link.sync(ffdkit, sphere), "the slider change was not applied"
    sync_ms.append(ms(t))
    t2 = time.perf_counter()
    view_layer.update()
    evaluate_ms.append(ms(t2))
    total.append(ms(t))
    assert np.abs(evaluated_points(sphere) - before).max() > 1e-3, "the slider did not move the mesh"
link.tool.points = original_points
key_write.write_points = original_write_points
path = link.write_path

# The write through foreach_set, for comparison (the path Blender offers without the direct copy).
points = link.tool.points()
foreach_ms = []
for k in range(reps):
    t = time.perf_counter()
    key_write.write_points(block, points, allow_direct=False)
    foreach_ms.append(ms(t))

# The other ways to the same evaluated mesh: the key written and the mesh tagged instead of the
# Key (a tagged mesh is copied whole for evaluation); no shape key, the mesh's own vertices
# written (foreach_set is fast there: MeshVertex.co maps onto MVert.co) and the mesh tagged.
mesh_tagged = []
for k in range(reps):
    scaled = points * (1 + 0.01 * (k + 1))
    t = time.perf_counter()
    key_write.write_points(block, scaled)
    sphere.data.update_tag()
    view_layer.update()
    mesh_tagged.append(ms(t))
assert bpy.ops.ffdkit.remove_tool() == {"FINISHED"}
rest = np.empty(3 * count, dtype=np.float32)
sphere.data.vertices.foreach_get("co", rest)
vertices_written = []
for k in range(reps):
    scaled = rest * np.float32(1 + 0.01 * (k + 1))
    t = time.perf_counter()
    sphere.data.vertices.foreach_set("co", scaled)
    sphere.data.update_tag()
    view_layer.update()
    vertices_written.append(ms(t))
sphere.data.vertices.foreach_set("co", rest)

# ---- Blender's Lattice modifier on the same mesh --------------------------------------------
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
    lattice.append(ms(t))
    assert np.abs(evaluated_points(sphere) - before).max() > 1e-3, "the lattice point did not move the mesh"

med = statistics.median
print("blender_slider_bench vertices %d, tool fig6-8 (fitted), median of %d, Blender %s"
      % (count, reps, bpy.app.version_string))
print("  load tool (embed + first write):                    %8.1f ms" % load_ms)
print("  ffdkit slider -> evaluated mesh:                    %8.1f ms" % med(total))
print("    the add-on's update (sliders, ffdkit, write, tag): %7.1f ms" % med(sync_ms))
print("      ffdkit's update (SceneDeformer):                %7.1f ms" % med(update_ms))
print("      write into the shape key (%s):            %7.1f ms  (foreach_set: %.1f ms)"
      % (path, med(write_ms), med(foreach_ms)))
print("    Blender's evaluation of the mesh:                 %7.1f ms" % med(evaluate_ms))
print("  the bare mesh re-evaluated (no tool, no modifier):  %8.1f ms" % med(floor))
print("  the key written, the mesh tagged instead of the Key: %8.1f ms" % med(mesh_tagged))
print("  no shape key, the mesh's vertices written and tagged: %7.1f ms" % med(vertices_written))
print("  Blender Lattice modifier 4x4x4 B-spline, point move -> evaluated mesh: %8.1f ms" % med(lattice))
