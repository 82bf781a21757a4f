"""Keys on a widget slider play back through Blender's animation system: keys at frames 1 and 24
(Blender's default Bezier keys, auto-clamped handles), and the mesh at frames 1, 12 and 24 equals
ffdkit's own animation evaluation (ffdkit-cli deform --scene --frame of a scene with the same
keys, smooth interpolation, 24 frames per second) within 1e-6. The tool stays at its stored frame
(not fitted), so the scene file needs no placement of its own."""

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
tool = os.path.join(support.SOURCE_DIR, "widgets", "examples", "fig6-8.json")
# Points inside the tool's unit-box lattice.
rest = support.sphere_points(count=500, centre=(0.5, 0.5, 0.5), radii=(0.4, 0.4, 0.4), seed=5)

support.empty_scene()
scene = bpy.context.scene
scene.render.fps = 24
obj = support.add_mesh("part", rest)
stored = support.vertices(obj)
assert bpy.ops.ffdkit.load_tool(filepath=tool, fit=False) == {"FINISHED"}

keys = {1: 0.0, 24: 0.3}
turn = {1: 0.0, 24: -0.5}
for frame in keys:
    obj["ffd:push-front"] = keys[frame]
    obj["ffd:turn-back"] = turn[frame]
    obj.keyframe_insert('["ffd:push-front"]', frame=frame)
    obj.keyframe_insert('["ffd:turn-back"]', frame=frame)

# ffdkit's side: the same keys in a scene file, at time frame / 24 s.
np.save(os.path.join(folder, "part.npy"), stored)
with open(tool, encoding="utf-8") as source, open(os.path.join(folder, "tool.json"), "w", encoding="utf-8") as copy:
    copy.write(source.read())
scene_file = {
    "format": "ffdkit-scene", "version": 2,
    "objects": [{"name": "part", "mesh": {"path": "part.npy"}}],
    "widgetFile": "tool.json",
    "attachments": [{"lattice": "lattice", "objects": ["part"]}],
    "animation": {"frameRate": 24.0, "frames": [0, 72], "channels": [
        {"widget": widget, "property": "variation",
         "keys": [{"time": frame / 24.0, "value": value, "interpolation": "smooth"} for frame, value in values.items()]}
        for widget, values in (("push-front", keys), ("turn-back", turn))]},
}
with open(os.path.join(folder, "scene.json"), "w", encoding="utf-8") as out:
    json.dump(scene_file, out)

for frame in (1, 12, 24, 6):
    scene.frame_set(frame)  # frame_change_post: the add-on reads the keyed values and writes the key
    out = os.path.join(folder, "frame%d.npy" % frame)
    support.run_cli("deform", "-q", "--scene", folder, "--frame", str(frame), "-o", out)
    expected = np.load(out)
    keyed = support.shape_key_points(obj)
    evaluated = support.evaluated_points(obj)
    error = max(np.abs(keyed - expected).max(), np.abs(evaluated - expected).max())
    moved = np.abs(expected - stored).max()
    print("frame %2d: push-front %.6f, moved %.4f, max |blender - ffdkit| %.2e"
          % (frame, obj.evaluated_get(bpy.context.evaluated_depsgraph_get())["ffd:push-front"], moved, error))
    assert error <= TOLERANCE, "frame %d: Blender differs from ffdkit's animation by %g" % (frame, error)
    if frame != 1:
        assert moved > 1e-2, "frame %d: the keys did not move the mesh" % frame

# A driver on a slider (frame / 100): the value Blender evaluates reaches the tool.
driver = obj.driver_add('["ffd:pull-back"]').driver
driver.type = "SCRIPTED"
driver.expression = "frame / 100"
scene.frame_set(20)
out = os.path.join(folder, "driven.npy")
support.run_cli("deform", "-q", "--scene", folder, "--frame", "20", "--set", "pull-back=0.2", "-o", out)
error = np.abs(support.shape_key_points(obj) - np.load(out)).max()
print("frame 20 with pull-back driven to 0.2: max |blender - ffdkit| %.2e" % error)
assert error <= TOLERANCE, "the driven slider: Blender differs from ffdkit by %g" % error
obj.driver_remove('["ffd:pull-back"]')
obj["ffd:pull-back"] = 0.0

# Bake to Shape Keys: frames 1..24 become shape keys, and with the add-on disabled (no handler)
# the animation plays back from them alone: at frames 6 and 12 the same positions.
live = {}
for frame in (6, 12):
    scene.frame_set(frame)
    live[frame] = support.shape_key_points(obj)
assert bpy.ops.ffdkit.bake_shape_keys(frame_start=1, frame_end=24, frame_step=1) == {"FINISHED"}
blocks = obj.data.shape_keys.key_blocks
assert blocks["ffdkit"].mute and all("ffdkit %d" % f in blocks for f in range(1, 25))
import addon_utils  # noqa: E402
addon_utils.disable("ffdkit_blender", default_set=True)
for frame in (12, 6):
    scene.frame_set(frame)
    error = np.abs(support.evaluated_points(obj) - live[frame]).max()
    print("baked frame %2d played back without the add-on: max |baked - live| %.2e" % (frame, error))
    assert error <= TOLERANCE, "frame %d: the baked keys differ from the live deformation by %g" % (frame, error)
