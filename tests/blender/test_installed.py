"""Run by installed_addon.cmake: the installed add-on, found by Blender among its system add-ons,
enables and imports the installed ffdkit module (not the build tree's), and loads a tool."""

import os
import sys

import addon_utils
import bpy
import numpy as np

prefix = os.environ["FFDKIT_PREFIX"]
assert "FFDKIT_PYTHONPATH" not in os.environ
names = [module.__name__ for module in addon_utils.modules(refresh=True)]
assert "ffdkit_blender" in names, "Blender does not list the installed add-on (it has %d add-ons)" % len(names)
module = addon_utils.enable("ffdkit_blender", default_set=True, handle_error=lambda error: sys.exit(repr(error)))
assert module.__file__.startswith(os.path.join(prefix, "share", "blender", "scripts", "addons")), module.__file__
ffdkit = module.ffdkit_module()
assert ffdkit.__file__.startswith(os.path.join(prefix, "lib", "python3", "dist-packages")), ffdkit.__file__
print("add-on %s with ffdkit %s" % (module.__file__, ffdkit.__file__))

mesh = bpy.data.meshes.new("part")
mesh.from_pydata([tuple(p) for p in np.random.default_rng(2).random((100, 3))], [], [])
obj = bpy.data.objects.new("part", mesh)
bpy.context.scene.collection.objects.link(obj)
bpy.context.view_layer.objects.active = obj
tool = os.path.join(prefix, "share", "ffdkit", "widgets", "fig6-2.json")
assert bpy.ops.ffdkit.load_tool(filepath=tool) == {"FINISHED"}
assert "ffd:red-ring" in obj.keys()
