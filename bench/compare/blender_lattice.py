# Blender's lattice modifier on the points and lattice of bench_ffd's BM_Deform, timed headless.
# Run by blender_lattice.sh:  blender -b --factory-startup --python blender_lattice.py -- POINTS REPS
# POINTS uniform random points in the unit box (no faces), a 4 x 4 x 4 lattice with cubic
# B-spline interpolation on every axis spanning the unit box, every lattice point moved by up to
# +-0.1 per coordinate (as BM_Deform's moved()). Prints one line: "blender_lattice_ms MEDIAN
# CPU_MEDIAN" = the median over REPS of (evaluation with the modifier) - (evaluation without it),
# wall and process CPU time, in ms.
import statistics
import sys
import time

import bpy
import numpy as np

args = sys.argv[sys.argv.index("--") + 1:]
count = int(args[0]) if args else 1000000
reps = int(args[1]) if len(args) > 1 else 5

bpy.ops.wm.read_factory_settings(use_empty=True)
rng = np.random.default_rng(1)
points = rng.random((count, 3))

mesh = bpy.data.meshes.new("points")
mesh.vertices.add(count)
mesh.vertices.foreach_set("co", points.astype(np.float32).ravel())
mesh.update()
obj = bpy.data.objects.new("points", mesh)
bpy.context.scene.collection.objects.link(obj)

lattice_data = bpy.data.lattices.new("lattice")
lattice_data.points_u = lattice_data.points_v = lattice_data.points_w = 4
lattice_data.interpolation_type_u = lattice_data.interpolation_type_v = "KEY_BSPLINE"
lattice_data.interpolation_type_w = "KEY_BSPLINE"
lattice = bpy.data.objects.new("lattice", lattice_data)
lattice.location = (0.5, 0.5, 0.5)  # the lattice spans [-0.5, 0.5]^3 in its own space
bpy.context.scene.collection.objects.link(lattice)
moves = np.random.default_rng(2).uniform(-0.1, 0.1, (len(lattice_data.points), 3))
for point, move in zip(lattice_data.points, moves):
    point.co_deform = tuple(np.array(point.co) + move)

modifier = obj.modifiers.new("lattice", "LATTICE")
modifier.object = lattice
depsgraph = bpy.context.evaluated_depsgraph_get()


def evaluate(enabled):
    modifier.show_viewport = enabled
    obj.data.update_tag()
    obj.update_tag(refresh={"DATA"})
    wall = time.perf_counter()
    cpu = time.process_time()
    depsgraph.update()
    evaluated = obj.evaluated_get(depsgraph)
    n = len(evaluated.data.vertices)
    wall = time.perf_counter() - wall
    cpu = time.process_time() - cpu
    assert n == count
    return wall, cpu


# Check once that the modifier moved the points.
evaluate(True)
moved = np.empty(3 * count, dtype=np.float32)
obj.evaluated_get(depsgraph).data.vertices.foreach_get("co", moved)
if not np.abs(moved.reshape(-1, 3) - points).max() > 1e-3:
    sys.exit("blender_lattice.py: the lattice modifier did not move the points")

walls, cpus = [], []
for _ in range(reps):
    with_wall, with_cpu = evaluate(True)
    without_wall, without_cpu = evaluate(False)
    walls.append(1000 * (with_wall - without_wall))
    cpus.append(1000 * (with_cpu - without_cpu))
print("blender_lattice_ms %.2f %.2f" % (statistics.median(walls), statistics.median(cpus)), flush=True)
