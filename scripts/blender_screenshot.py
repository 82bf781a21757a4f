"""Renders docs/images/blender-vise.png: ffdkit's vise tool on the Stanford bunny in Blender, the
bunny as loaded on the left and squeezed by the vise (its handle turned) on the right, in
Blender's workbench engine. Needs an X display (the workbench renders with OpenGL) and the bunny,
which the repository does not hold (the Stanford 3D Scanning Repository's bunny, as an OBJ or
PLY file: for example data/stanford-bunny.obj of github.com/alecjacobson/common-3d-test-models):

    FFDKIT_PYTHONPATH=build/python xvfb-run -a -s "-screen 0 1280x1024x24" \\
        blender -b --factory-startup --python scripts/blender_screenshot.py -- \\
        docs/images/blender-vise.png path/to/stanford-bunny.obj
"""

import math
import os
import sys
import tempfile

import addon_utils
import bpy
import numpy as np

arguments = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if len(arguments) != 2:
    sys.exit("usage: blender -b --factory-startup --python scripts/blender_screenshot.py -- OUTPUT.png BUNNY.obj|.ply")
out, bunny_path = (os.path.abspath(a) for a in arguments)
if not os.path.isfile(bunny_path):
    sys.exit("%s: no such file (the Stanford bunny as OBJ or PLY)" % bunny_path)
root = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.join(root, "blender"))
addon_utils.enable("ffdkit_blender", default_set=True).ffdkit_module()
import ffdkit  # noqa: E402  (found by the add-on)

for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
vise = os.path.join(tempfile.mkdtemp(prefix="ffdkit-screenshot-"), "vise.json")
ffdkit.scenes.writeWidgetFile(vise, ffdkit.scenes.readScene(os.path.join(root, "scenes", "examples", "vise")).widgets)


def load_bunny(x):
    """The bunny, Z up, 2 units tall, standing on z = 0 at (x, 0), smooth shaded."""
    before = set(bpy.data.objects)
    if bunny_path.lower().endswith(".ply"):
        bpy.ops.import_mesh.ply(filepath=bunny_path)
    else:
        bpy.ops.wm.obj_import(filepath=bunny_path)
    (bunny,) = set(bpy.data.objects) - before
    points = np.empty(3 * len(bunny.data.vertices), dtype=np.float32)
    bunny.data.vertices.foreach_get("co", points)
    points = points.reshape(-1, 3).astype(np.float64)
    points = points[:, [0, 2, 1]] * [1, -1, 1]  # the scan's own coordinates, Y up, to Blender's Z up
    lo, hi = points.min(axis=0), points.max(axis=0)
    points = (points - [(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, lo[2]]) * (2.0 / (hi[2] - lo[2])) + [x, 0, 0]
    bunny.data.vertices.foreach_set("co", points.astype(np.float32).ravel())
    bunny.data.update()
    bunny.matrix_world.identity()  # the importer's axis conversion is replaced by the one above
    bunny.data.polygons.foreach_set("use_smooth", [True] * len(bunny.data.polygons))
    return bunny


bunnies = [load_bunny(x) for x in (-1.5, 1.5)]
bpy.context.view_layer.objects.active = bunnies[1]
assert bpy.ops.ffdkit.load_tool(filepath=vise, fit=True) == {"FINISHED"}
bunnies[1]["ffd:handle"] = 14.0  # about two turns: the jaws close by the handle's gain, clamped
bunnies[1].update_tag()
bpy.context.view_layer.update()
os.remove(vise)

scene = bpy.context.scene
bpy.ops.object.camera_add(location=(0, -9.0, 1.6), rotation=(math.radians(85), 0, 0))
scene.camera = bpy.context.active_object
scene.camera.data.lens = 45
scene.render.engine = "BLENDER_WORKBENCH"
scene.display.shading.light = "STUDIO"
scene.display.shading.color_type = "SINGLE"
scene.display.shading.single_color = (0.8, 0.6, 0.35)
scene.display.shading.show_cavity = True
scene.render.resolution_x, scene.render.resolution_y = 1200, 600
scene.render.film_transparent = False
scene.world = bpy.data.worlds.new("world") if scene.world is None else scene.world
scene.render.filepath = out
bpy.ops.render.render(write_still=True)
print("wrote", out)
