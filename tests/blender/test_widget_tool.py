"""A widget file loaded onto a Blender mesh (fitted, as ffdkit-cli deform --fit places it) gives,
for five variations of each sample tool, the vertex positions ffdkit-cli deform gives for the
same points and the same --set values: in the add-on's shape key and in the evaluated mesh,
within 1e-6 (Blender stores float32). A bound widget's slider follows its leader."""

import json
import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_support as support  # noqa: E402

support.enable_addon()
import ffdkit  # noqa: E402  (found by the add-on)

TOLERANCE = 1e-6
folder = support.temporary_folder()

tools = {os.path.splitext(name)[0]: os.path.join(support.SOURCE_DIR, "widgets", "examples", name)
         for name in sorted(os.listdir(os.path.join(support.SOURCE_DIR, "widgets", "examples")))}
vise = os.path.join(folder, "vise.json")
ffdkit.scenes.writeWidgetFile(vise, ffdkit.scenes.readScene(os.path.join(support.SOURCE_DIR, "scenes", "examples", "vise")).widgets)
tools["vise"] = vise
assert len(tools) == 5, tools

SPAN = {"TRANSLATE": 0.25, "ROTATE": 0.6, "SCALE": 0.3}
rest = support.sphere_points()
worst = {}
for tool_name, path in tools.items():
    model = ffdkit.scenes.readWidgetFile(path)
    affines = [(model.name(w), model.affineKind(w).name.upper()) for w in model.widgets(ffdkit.widgets.WidgetType.Affine)]
    assert affines, tool_name
    rng = np.random.default_rng(len(tool_name))
    worst[tool_name] = 0.0
    for variation in range(5):
        # Variation v moves widget v (mod the count) and, from the third on, one more: bindings
        # and several changes in one update are both exercised.
        chosen = {affines[variation % len(affines)][0]}
        if variation >= 2:
            chosen.add(affines[(variation * 3 + 1) % len(affines)][0])
        values = [(name, float(rng.uniform(0.3, 1) * SPAN[kind] * (20 if tool_name == "vise" and kind == "ROTATE" else 1)))
                  for name, kind in affines if name in chosen]

        support.empty_scene()
        obj = support.add_mesh("part", rest)
        stored = support.vertices(obj)
        assert bpy.ops.ffdkit.load_tool(filepath=path, fit=True) == {"FINISHED"}
        for name, value in values:
            obj["ffd:" + name] = value
        obj.update_tag()  # what a slider's change does (rna_property_update tags the object)
        bpy.context.view_layer.update()

        np.save(os.path.join(folder, "in.npy"), stored)
        out = os.path.join(folder, "out.npy")
        arguments = ["deform", "-q", "-w", path, os.path.join(folder, "in.npy"), "-o", out, "--fit"]
        for name, value in values:
            arguments += ["--set", "%s=%r" % (name, value)]
        support.run_cli(*arguments)
        expected = np.load(out)
        keyed = support.shape_key_points(obj)
        evaluated = support.evaluated_points(obj)
        moved = np.abs(expected - stored).max()
        error = max(np.abs(keyed - expected).max(), np.abs(evaluated - expected).max())
        worst[tool_name] = max(worst[tool_name], error)
        print("%-14s variation %d %-60s moved %.4f  max |blender - cli| %.2e"
              % (tool_name, variation, json.dumps(values), moved, error))
        assert moved > 1e-3, "%s %s: the tool did not move the mesh (%g)" % (tool_name, values, moved)
        assert error <= TOLERANCE, "%s %s: Blender differs from ffdkit-cli by %g" % (tool_name, values, error)
        # The rest shape stays in the reference key; the vertices are not overwritten.
        assert np.array_equal(support.vertices(obj), stored)

# A bound follower's slider shows ffdkit's value: the vise's handle drives both jaws.
support.empty_scene()
obj = support.add_mesh("part", rest)
assert bpy.ops.ffdkit.load_tool(filepath=vise, fit=True) == {"FINISHED"}
obj["ffd:handle"] = 6.0
obj.update_tag()
bpy.context.view_layer.update()
model = ffdkit.scenes.readWidgetFile(vise)
model.setVariation(model.find("handle"), 6.0)
for jaw in ("left-jaw", "right-jaw"):
    assert abs(obj["ffd:" + jaw] - model.variation(model.find(jaw))) < 1e-12, (jaw, obj["ffd:" + jaw])
    assert abs(obj["ffd:" + jaw]) > 1e-3, jaw

# Saved and opened again: the tool is rebuilt as it was posed (the jaws are not moved twice), and
# the next slider change deforms as ffdkit-cli does with both changes.
blend = os.path.join(folder, "vise.blend")
bpy.ops.wm.save_as_mainfile(filepath=blend)
bpy.ops.wm.open_mainfile(filepath=blend)
obj = bpy.data.objects["part"]
obj["ffd:handle"] = 9.0
obj.update_tag()
bpy.context.view_layer.update()
np.save(os.path.join(folder, "in.npy"), support.vertices(obj))
out = os.path.join(folder, "out.npy")
support.run_cli("deform", "-q", "-w", vise, os.path.join(folder, "in.npy"), "-o", out, "--fit",
                "--set", "handle=6.0", "--set", "handle=9.0")
error = np.abs(support.shape_key_points(obj) - np.load(out)).max()
print("vise saved, opened, handle 6 -> 9: max |blender - cli| %.2e" % error)
assert error <= TOLERANCE, "after reopening, Blender differs from ffdkit-cli by %g" % error
print("max error per tool:", json.dumps(worst))
