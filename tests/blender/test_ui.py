"""The add-on's panel in a Blender window, driven by real mouse and key events
(--enable-event-simulate; needs a display: scripts/test.sh runs ctest under Xvfb):
a click on the sidebar's ffdkit tab shows the panel; I over a slider keys that widget's variation;
a drag on the slider (of the tool loaded afresh) changes it, and the mesh's shape key follows as
ffdkit deforms it.
    blender --factory-startup --enable-event-simulate --python tests/blender/test_ui.py
Runs from timers (the window must be up); exits with os._exit: 0 passed, 1 failed."""

import os
import sys
import traceback

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_support as support  # noqa: E402

module = support.enable_addon()
tool_path = os.path.join(support.SOURCE_DIR, "widgets", "examples", "fig6-2.json")
drawn = []
draw = module.FFDKIT_PT_tool.draw


def recording_draw(self, context):
    try:
        draw(self, context)
        drawn.append(None)
    except Exception as error:  # reported by the check below
        drawn.append(error)
        raise


module.FFDKIT_PT_tool.draw = recording_draw
state = {"step": "setup", "y": 0, "tries": 0}


def fail(message):
    print("FAILED:", message, flush=True)
    os._exit(1)


def click(window, x, y):
    window.event_simulate(type="MOUSEMOVE", value="NOTHING", x=x, y=y)
    window.event_simulate(type="LEFTMOUSE", value="PRESS", x=x, y=y)
    window.event_simulate(type="LEFTMOUSE", value="RELEASE", x=x, y=y)


def keyed(obj):
    data = obj.animation_data
    return [] if data is None or data.action is None else [c.data_path for c in data.action.fcurves]


def step():
    try:
        return run_step()
    except Exception:
        traceback.print_exc()
        fail("an exception in the test")


def run_step():
    window = bpy.context.window_manager.windows[0]
    area = next(a for a in window.screen.areas if a.type == "VIEW_3D")
    region = next(r for r in area.regions if r.type == "UI")
    obj = bpy.data.objects["Cube"]
    if state["step"] == "setup":
        area.spaces.active.show_region_ui = True
        bpy.context.view_layer.objects.active = obj
        with bpy.context.temp_override(window=window, area=area):
            if bpy.ops.ffdkit.load_tool(filepath=tool_path) != {"FINISHED"}:
                fail("Load Widget Tool failed")
        state["rest"] = support.shape_key_points(obj)
        state["step"] = "tab"
        return 0.3
    if state["step"] == "tab":  # click down the sidebar's tab strip until the ffdkit tab opens
        if any(d is not None for d in drawn):
            fail("the panel's draw raised %r" % next(d for d in drawn if d is not None))
        if drawn:
            print("the ffdkit tab opened by a click %d px below the sidebar's top" % state["y"])
            state["step"], state["y"] = "key", 40
            return 0.3
        if state["y"] > region.height:
            fail("no click on the sidebar's tabs showed the ffdkit panel")
        click(window, region.x + region.width - 10, region.y + region.height - 10 - state["y"])
        state["y"] += 12
        return 0.1
    if state["step"] == "key":  # I over each row of the panel until one keys a slider
        paths = keyed(obj)
        if paths:
            if len(paths) != 1 or not paths[0].startswith('["ffd:'):
                fail("I keyed %s" % paths)
            state["path"], state["row"] = paths[0], state["y"] - 6
            print("I over the row %d px below the panel's top keyed %s" % (state["row"], paths[0]))
            state["step"] = "drag"
            return 0.3
        if state["y"] > region.height:
            fail("pressing I over the panel's rows keyed nothing")
        x, y = region.x + region.width // 2, region.y + region.height - state["y"]
        window.event_simulate(type="MOUSEMOVE", value="NOTHING", x=x, y=y)
        window.event_simulate(type="I", value="PRESS", x=x, y=y)
        window.event_simulate(type="I", value="RELEASE", x=x, y=y)
        state["y"] += 6
        return 0.1
    if state["step"] == "drag":  # a fresh tool (the key scan may have nudged other sliders), then drag
        with bpy.context.temp_override(window=window, area=area):
            if bpy.ops.ffdkit.load_tool(filepath=tool_path) != {"FINISHED"}:
                fail("Load Widget Tool failed")
        if keyed(obj):
            fail("loading the tool again left keys %s" % keyed(obj))
        key = state["path"][2:-2]
        state["before"] = float(obj[key])
        x, y = region.x + region.width // 2, region.y + region.height - state["row"]
        window.event_simulate(type="MOUSEMOVE", value="NOTHING", x=x, y=y)
        window.event_simulate(type="LEFTMOUSE", value="PRESS", x=x, y=y)
        for dx in range(5, 65, 5):
            window.event_simulate(type="MOUSEMOVE", value="NOTHING", x=x + dx, y=y)
        window.event_simulate(type="LEFTMOUSE", value="RELEASE", x=x + 60, y=y)
        state["step"] = "check"
        return 0.5
    key = state["path"][2:-2]
    value = float(obj[key])
    if not value > state["before"]:
        fail("dragging the %s slider right left it at %g (was %g)" % (key, value, state["before"]))
    import ffdkit
    from ffdkit_blender import tool as tool_module
    expected_tool = tool_module.Tool(ffdkit, obj["_ffdkit_tool"], support.vertices(obj))
    expected_tool.set_variations({k[4:]: float(obj[k]) for k in obj.keys() if k.startswith("ffd:")})
    expected = expected_tool.points()
    error = np.abs(support.shape_key_points(obj) - expected).max()
    print("dragged %s from %g to %g: max |shape key - ffdkit| %.2e" % (key, state["before"], value, error))
    if error > 1e-6 or np.abs(expected - state["rest"]).max() < 1e-4:
        fail("the shape key does not follow the dragged slider")
    print("passed", flush=True)
    os._exit(0)


bpy.app.timers.register(step, first_interval=1.0)
