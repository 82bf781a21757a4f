"""Bad input to Load Widget Tool: a broken widget file, a missing file, a non-mesh active object,
no active object, a mesh with no vertices, a mesh in edit mode, a tool whose lattices (at their
stored frames) reach no vertex. Each is reported through the operator's report (Blender raises
it to a Python caller as RuntimeError "Error: ..."), with no traceback, and leaves the object as
it was: same vertices, no shape keys, no properties."""

import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_support as support  # noqa: E402

support.enable_addon()

folder = support.temporary_folder()
tool = os.path.join(support.SOURCE_DIR, "widgets", "examples", "fig6-8.json")
broken = os.path.join(folder, "broken.json")
with open(tool, encoding="utf-8") as source:
    text = source.read()
with open(broken, "w", encoding="utf-8") as out:
    out.write(text[: len(text) // 2])  # cut in the middle
wrong = os.path.join(folder, "wrong.json")
with open(wrong, "w", encoding="utf-8") as out:
    out.write(text.replace('"counts": [', '"counts": [-7, ', 1))


def expect_report(expected, **arguments):
    try:
        result = bpy.ops.ffdkit.load_tool(**arguments)
    except RuntimeError as error:
        message = str(error)
        print("reported:", message.strip())
        assert message.startswith("Error:"), message
        assert "Traceback" not in message, message
        assert expected in message, "expected %r in the report, got %r" % (expected, message)
        return
    raise AssertionError("no error reported (the operator returned %s)" % result)


def untouched(obj, points):
    if obj.type == "MESH":
        assert obj.data.shape_keys is None, "%s got shape keys" % obj.name
        assert np.array_equal(support.vertices(obj), points), "%s's vertices changed" % obj.name
    assert not [k for k in obj.keys() if k.startswith("ffd") or k.startswith("_ffdkit")], list(obj.keys())


support.empty_scene()
rest = support.sphere_points()
obj = support.add_mesh("part", rest)
stored = support.vertices(obj)
expect_report("broken.json", filepath=broken)
untouched(obj, stored)
expect_report("wrong.json", filepath=wrong)
untouched(obj, stored)
expect_report("no such widget file", filepath=os.path.join(folder, "absent.json"))
untouched(obj, stored)

# The tool at its stored frame (the unit box) while the mesh lies far away.
obj.data.vertices.foreach_set("co", (rest + 10.0).astype(np.float32).ravel())
obj.data.update()
stored_far = support.vertices(obj)
expect_report("reach none of the 400 vertices of 'part'", filepath=tool, fit=False)
untouched(obj, stored_far)

empty = support.add_mesh("empty", np.zeros((0, 3)))
expect_report("'empty' has no vertices", filepath=tool)
untouched(empty, np.zeros((0, 3)))

camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
bpy.context.scene.collection.objects.link(camera)
bpy.context.view_layer.objects.active = camera
expect_report("'camera' is a camera, not a mesh", filepath=tool)
untouched(camera, None)

bpy.context.view_layer.objects.active = None
expect_report("no active object", filepath=tool)

# A mesh in edit mode: its vertices live in the edit mesh, so the tool is refused.
bpy.context.view_layer.objects.active = obj
bpy.ops.object.mode_set(mode="EDIT")
expect_report("'part' is in edit mode", filepath=tool)
bpy.ops.object.mode_set(mode="OBJECT")
untouched(obj, stored_far)

# After all of that, a good load still works on the same mesh.
bpy.context.view_layer.objects.active = obj
obj.data.vertices.foreach_set("co", rest.astype(np.float32).ravel())
obj.data.update()
assert bpy.ops.ffdkit.load_tool(filepath=tool) == {"FINISHED"}
assert obj.data.shape_keys is not None and "ffdkit" in obj.data.shape_keys.key_blocks
print("bad input: every case reported, nothing changed")
