"""The add-on as a user installs it: ffdkit_blender.zip (the build's zip target) through
Preferences > Add-ons > Install (bpy.ops.preferences.addon_install) into an empty user scripts
folder (BLENDER_USER_SCRIPTS, set by CTest), enabled in a factory-startup Blender: it finds the
ffdkit module, registers its operators, panel and handlers, loads a tool, and unregisters cleanly."""

import filecmp
import os
import shutil
import sys

import addon_utils
import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_support as support  # noqa: E402

zip_path = support.env("FFDKIT_BLENDER_ZIP")
user_scripts = support.env("BLENDER_USER_SCRIPTS")
assert os.path.isfile(zip_path), "%s is missing: build the ffdkit_blender_zip target" % zip_path
installed = os.path.join(user_scripts, "addons", "ffdkit_blender")
shutil.rmtree(installed, ignore_errors=True)

assert bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True) == {"FINISHED"}
source = os.path.join(support.env("FFDKIT_ADDON_DIR"), "ffdkit_blender")
for name in sorted(os.listdir(source)):
    if name.endswith(".py"):
        assert filecmp.cmp(os.path.join(source, name), os.path.join(installed, name), shallow=False), \
            "the zip's %s differs from the source (rebuild ffdkit_blender_zip)" % name

module = addon_utils.enable("ffdkit_blender", default_set=True, handle_error=lambda error: sys.exit(
    "enabling the installed add-on failed: %r" % error))
assert module is not None
assert os.path.dirname(module.__file__) == installed, module.__file__
assert module.bl_info["blender"] <= bpy.app.version, (module.bl_info["blender"], bpy.app.version)
ffdkit = module.ffdkit_module()
print("add-on from %s, ffdkit %s from %s" % (module.__file__, ffdkit.__version__, ffdkit.__file__))
for operator in ("load_tool", "remove_tool"):
    assert hasattr(bpy.ops.ffdkit, operator), operator
assert hasattr(bpy.types, "FFDKIT_PT_tool")
assert module._after_evaluation in bpy.app.handlers.depsgraph_update_post and module._before_frame in bpy.app.handlers.frame_change_pre

support.empty_scene()
obj = support.add_mesh("part", support.sphere_points())
assert bpy.ops.ffdkit.load_tool(filepath=os.path.join(support.SOURCE_DIR, "widgets", "examples", "fig6-2.json")) == {"FINISHED"}
assert sorted(k for k in obj.keys() if k.startswith("ffd:")) == ["ffd:blue-arrow", "ffd:green-arrow", "ffd:red-ring"]
assert bpy.ops.ffdkit.remove_tool() == {"FINISHED"}
assert obj.data.shape_keys is None and not [k for k in obj.keys() if k.startswith("ffd")]

addon_utils.disable("ffdkit_blender", default_set=True)
assert not hasattr(bpy.types, "FFDKIT_PT_tool")
assert module._after_evaluation not in bpy.app.handlers.depsgraph_update_post
print("installed, enabled, used and disabled")
