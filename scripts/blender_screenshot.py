"""Renders docs/images/blender-vise.png: the vise tool squeezing Blender's monkey (Suzanne), the
mesh as loaded on the left and with the vise's handle turned on the right, in Blender's
workbench engine. Needs an X display (the workbench renders with OpenGL):

    FFDKIT_PYTHONPATH=build/python xvfb-run -a -s "-screen 0 1280x1024x24" \\
        blender -b --factory-startup --python blender/screenshot.py -- docs/images/blender-vise.png
"""

import math
import os
import sys
import tempfile

import addon_utils
import bpy

out = os.path.abspath(sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else "blender-vise.png")
root = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.join(root, "blender"))
addon_utils.enable("ffdkit_blender", default_set=True).ffdkit_module()

for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
vise = os.path.join(tempfile.mkdtemp(prefix="ffdkit-screenshot-"), "vise.json")
import ffdkit  # noqa: E402  (found by the add-on)

ffdkit.scenes.writeWidgetFile(vise, ffdkit.scenes.readScene(os.path.join(root, "scenes", "examples", "vise")).widgets)

monkeys = []
for x in (-1.3, 1.3):
    bpy.ops.mesh.primitive_monkey_add(size=2.0, location=(x, 0, 0))
    monkey = bpy.context.active_object
    subdivision = monkey.modifiers.new("subdivision", "SUBSURF")
    subdivision.levels = 2
    bpy.ops.object.modifier_apply(modifier=subdivision.name)
    bpy.ops.object.shade_smooth()
    monkeys.append(monkey)
bpy.context.view_layer.objects.active = monkeys[1]
assert bpy.ops.ffdkit.load_tool(filepath=vise, fit=True) == {"FINISHED"}
monkeys[1]["ffd:handle"] = 14.0  # about two turns: the jaws close by the handle's gain, clamped
monkeys[1].update_tag()
bpy.context.view_layer.update()
bpy.context.view_layer.update()
os.remove(vise)

scene = bpy.context.scene
bpy.ops.object.camera_add(location=(0, -8.0, 0.3), rotation=(math.radians(88), 0, 0))
scene.camera = bpy.context.active_object
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
