"""ffdkit scenes in Blender: Import ffdkit Scene turns each sample scene's objects into meshes with
its tool and keys; at several frames their evaluated points equal ffdkit-cli deform --scene
--frame of the same scene within 1e-6. New keys set in Blender, written back with Export ffdkit
Scene, play the same in ffdkit: the exported scene at a frame equals Blender at that frame."""

import json
import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_support as support  # noqa: E402

support.enable_addon()

TOLERANCE = 1e-6
folder = support.temporary_folder()
examples = os.path.join(support.SOURCE_DIR, "scenes", "examples")


def compare(scene_path, obj, frame, label):
    bpy.context.scene.frame_set(frame)
    out = os.path.join(folder, "out.npy")
    support.run_cli("deform", "-q", "--scene", scene_path, "--object", obj["_ffdkit_object"],
                    "--frame", str(frame), "-o", out)
    expected = np.load(out)
    error = np.abs(support.evaluated_points(obj) - expected).max()
    print("%-34s frame %3d: max |blender - ffdkit| %.2e" % (label, frame, error))
    assert error <= TOLERANCE, "%s at frame %d: Blender differs from ffdkit by %g" % (label, frame, error)


# The default scene with a monotone run of smooth keys (0, 0.1, 0.45 at 0, 1, 2.5 s): ffdkit's
# slope at the middle key is the finite difference, which Blender's automatic handles do not give.
with open(os.path.join(examples, "default", "scene.json"), encoding="utf-8") as source:
    monotone = json.load(source)
monotone["animation"]["channels"][0]["keys"] = [
    {"time": t, "value": v, "interpolation": "smooth"} for t, v in ((0.0, 0.0), (1.0, 0.1), (2.5, 0.45))]
os.makedirs(os.path.join(folder, "monotone"))
with open(os.path.join(folder, "monotone", "scene.json"), "w", encoding="utf-8") as out:
    json.dump(monotone, out)

for name, frames in (("press", (0, 1, 30, 72)), ("vise", (1,)), ("hierarchy", (1,)), ("default", (0, 12, 24, 36, 48, 60, 72)),
                     (os.path.join(folder, "monotone"), (12, 24, 31, 50, 60, 70))):
    support.empty_scene()
    path = os.path.join(examples, name)
    assert bpy.ops.ffdkit.import_scene(filepath=path) == {"FINISHED"}
    imported = [o for o in bpy.data.objects if "_ffdkit_object" in o.keys()]
    assert imported, name
    for obj in imported:
        for frame in frames:
            compare(path, obj, frame, "%s/%s" % (os.path.basename(name), obj.name))

# Keys made in Blender go back to the scene file.
support.empty_scene()
assert bpy.ops.ffdkit.import_scene(filepath=os.path.join(examples, "vise")) == {"FINISHED"}
obj = bpy.data.objects["part"]
bpy.context.view_layer.objects.active = obj
for frame, value in ((10, 0.0), (40, 9.0)):
    obj["ffd:handle"] = value
    obj.keyframe_insert('["ffd:handle"]', frame=frame)
exported = os.path.join(folder, "vise-keyed", "scene.json")
os.makedirs(os.path.dirname(exported))
assert bpy.ops.ffdkit.export_scene(filepath=exported) == {"FINISHED"}
obj["_ffdkit_object"] = "part"
for frame in (10, 25, 40):
    compare(os.path.dirname(exported), obj, frame, "vise keyed in Blender, exported")

# A monotone run of keys set in Blender (automatic handles) has a slope at its middle key that
# ffdkit's smooth keys would not give it: the export says so.
obj["ffd:handle"] = 12.0
obj.keyframe_insert('["ffd:handle"]', frame=70)
from ffdkit_blender import scene_io  # noqa: E402
import ffdkit  # noqa: E402
notes = scene_io.export_scene(ffdkit, [obj], obj["_ffdkit_scene"], exported, 24.0)
print("export notes:", notes)
assert len(notes) == 1 and "frame 40" in notes[0] and "plays it differently" in notes[0], notes
