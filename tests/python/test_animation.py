"""ffdkit.scenes from Python: a scene's objects and lattices, and its keyframed animation (keys,
interpolation, evaluation through the widget model, scene files), against values worked out by
hand here and the scene file's own JSON."""

import json
import math
import pathlib

import numpy as np
import pytest

import ffdkit
from ffdkit import scenes, widgets

ROOT = pathlib.Path(__file__).resolve().parents[2]
DEFAULT = ROOT / "scenes" / "examples" / "default" / "scene.json"
V = scenes.ChannelKind.Variation


def knob_and_push():
    """A knob on the top slab driving a push on a side face (gain 0.1), in an empty scene."""
    scene = scenes.Scene()
    model = widgets.WidgetModel()
    box = model.addLattice("box", (3, 3, 3))
    knob = model.addAffine(model.addCell(box, widgets.CellSpec.slab(2, 2), "top"), widgets.AffineKind.Rotate, "knob")
    push = model.addAffine(model.addCell(box, widgets.CellSpec.face(0, 0, 0, 0), "side"),
                           widgets.AffineKind.Translate, "push")
    model.bind(knob, push, widgets.ConversionRule(0.1))
    scene.widgets = model
    return scene, scene.widgets.find("knob"), scene.widgets.find("push")


def smoothstep(s):
    """A cubic Hermite segment with both slopes 0, as a fraction of the way: 3s^2 - 2s^3."""
    return 3 * s * s - 2 * s ** 3


# ---- the sample scene's keys ---------------------------------------------------------------------
def test_the_sample_scenes_keys_are_those_of_its_file():
    scene = scenes.readScene(DEFAULT)
    channel = json.loads(DEFAULT.read_text())["animation"]["channels"][0]
    pull = scene.widgets.find(channel["widget"])
    assert scene.keyTimes() == [key["time"] for key in channel["keys"]]
    assert scene.keyTimes(pull) == scene.keyTimes()
    for key in channel["keys"]:
        assert scene.keyValue(pull, V, key["time"]) == key["value"]
    assert scene.framesPerSecond == 24.0 and scene.frameRange == (0, 72)
    assert scene.frameTime(36) == 1.5


def test_smooth_keys_are_flat_at_extrema_and_ends():
    # default: pull keyed 0 -> 0.5 -> -0.2 -> 0 at 0, 1, 2, 3 s, all smooth. The ends and the two
    # extrema (0.5 and -0.2) get slope 0, so each segment is a plain smoothstep between its keys.
    scene = scenes.readScene(DEFAULT)
    pull = scene.widgets.find("pull")
    for seconds, expected in [(0.25, 0.5 * smoothstep(0.25)), (0.5, 0.25), (1.0, 0.5),
                              (1.75, 0.5 - 0.7 * smoothstep(0.75)), (2.5, -0.2 + 0.2 * smoothstep(0.5))]:
        scene.applyAnimation(seconds)
        assert scene.widgets.variation(pull) == pytest.approx(expected, abs=1e-12), seconds
    scene.applyAnimationFrame(24)  # 1 s at 24 fps: exactly the key
    assert scene.widgets.variation(pull) == 0.5


def test_the_animation_moves_the_deformed_points():
    scene = scenes.readScene(DEFAULT)
    scene.applyAnimation(0.0)
    rest = scenes.deformScene(scene)
    scene.applyAnimation(1.0)
    pulled = scenes.deformScene(scene)
    assert rest.keys() == pulled.keys()
    moved = max(np.abs(pulled[name] - rest[name]).max() for name in rest)
    assert moved > 1e-3


# ---- keys set from Python ------------------------------------------------------------------------
def test_linear_and_constant_keys_and_the_bound_widget_follows():
    scene, knob, push = knob_and_push()
    assert scene.setKey(knob, V, 0.0, 0.0, scenes.Interpolation.Linear) is None
    scene.setKey(knob, V, 2.0, 1.0, scenes.Interpolation.Constant)
    scene.setKey(knob, V, 4.0, 3.0)
    scene.applyAnimation(0.5)
    assert scene.widgets.variation(knob) == pytest.approx(0.25, abs=1e-15)
    assert scene.widgets.variation(push) == pytest.approx(0.025, abs=1e-15)  # gain 0.1
    scene.applyAnimation(3.999)  # a constant key holds until the next key
    assert scene.widgets.variation(knob) == 1.0
    scene.applyAnimation(4.0)
    assert scene.widgets.variation(knob) == 3.0
    assert scene.keyableKinds(knob) == [V]


def test_replacing_and_removing_keys_return_the_old_value():
    scene, knob, _ = knob_and_push()
    scene.setKey(knob, V, 1.0, 0.3)
    assert scene.setKey(knob, V, 1.0, 0.7) == 0.3
    assert scene.keyValue(knob, V, 1.0) == 0.7
    assert scene.removeKey(knob, V, 1.0) == 0.7
    assert scene.removeKey(knob, V, 1.0) is None
    assert scene.keyTimes() == []


def test_keyed_control_points_are_shown_exactly():
    scene, _, _ = knob_and_push()
    box = scene.widgets.find("box")
    rest = np.array(scene.widgets.controlPoints(box))
    lifted = rest + np.array([0.0, 0.0, 0.25])
    scene.setKey(box, scenes.ChannelKind.ControlPoints, 0.0, rest, scenes.Interpolation.Linear)
    scene.setKey(box, scenes.ChannelKind.ControlPoints, 1.0, lifted, scenes.Interpolation.Linear)
    scene.applyAnimation(0.5)
    np.testing.assert_allclose(scene.widgets.controlPoints(box), rest + [0.0, 0.0, 0.125], rtol=0, atol=1e-15)
    np.testing.assert_array_equal(scene.keyValue(box, scenes.ChannelKind.ControlPoints, 1.0), lifted)


def test_key_current_keys_the_present_value():
    scene, knob, _ = knob_and_push()
    scene.widgets.setVariation(knob, 0.4)
    scene.keyCurrent(knob, V, 2.0)
    assert scene.keyValue(knob, V, 2.0) == pytest.approx(0.4, abs=1e-15)


def test_keys_round_trip_through_a_scene_file_byte_for_byte(tmp_path):
    scene, knob, _ = knob_and_push()
    scene.setKey(knob, V, 0.0, 0.0, scenes.Interpolation.Linear)
    scene.setKey(knob, V, 1.0 / 3.0, 0.1, scenes.Interpolation.Constant)
    scene.setKey(knob, V, 2.5, -math.pi)
    scene.framesPerSecond = 30.0
    scene.frameRange = (-5, 100)
    path = tmp_path / "keyed.json"
    scenes.writeScene(path, scene)
    back = scenes.readScene(path)
    assert back.keyTimes() == scene.keyTimes() == [0.0, 1.0 / 3.0, 2.5]
    assert back.keyValue(back.widgets.find("knob"), V, 2.5) == -math.pi
    assert back.framesPerSecond == 30.0 and back.frameRange == (-5, 100)
    assert scenes.sceneFileText(back) == path.read_text()


# ---- errors --------------------------------------------------------------------------------------
def test_bad_keys_and_times_raise_animation_errors():
    scene, knob, _ = knob_and_push()
    with pytest.raises(ffdkit.AnimationError, match="finite"):
        scene.setKey(knob, V, math.nan, 1.0)
    with pytest.raises(ValueError):  # AnimationError is a ValueError too
        scene.setKey(scene.widgets.find("top"), V, 0.0, 1.0)  # a cell has nothing to key
    with pytest.raises(ffdkit.AnimationError):
        scene.applyAnimation(math.inf)
    with pytest.raises(ffdkit.AnimationError):
        scene.framesPerSecond = 0.0
    assert scene.framesPerSecond == 24.0
    with pytest.raises(ValueError, match="after the last"):
        scene.frameRange = (5, 1)
    with pytest.raises(ffdkit.AnimationError):
        scene.setKey(scene.widgets.find("box"), scenes.ChannelKind.ControlPoints, 0.0, np.zeros((5, 3)))


# ---- objects and lattices ------------------------------------------------------------------------
def test_a_y_up_mesh_file_stands_up_and_a_lattice_fits_around_it():
    path = ROOT / "tests" / "data" / "y_up_column.obj"
    raw = scenes.readMesh(path).points
    scene = scenes.Scene()
    scene.addMeshFile("column", str(path), up="y")
    points = scene.findObject("column").mesh.points
    # Y-up to Z-up: (x, y, z) -> (x, -z, y), a rotation of +90 degrees about x.
    np.testing.assert_array_equal(points, np.column_stack([raw[:, 0], -raw[:, 2], raw[:, 1]]))
    lattice = scene.attachNewLattice(["column"], name="cage", counts=(2, 2, 4), padding=0.1)
    assert scene.widgets.name(lattice) == "cage" and tuple(scene.widgets.counts(lattice)) == (2, 2, 4)
    assert scene.latticesDeforming("column") == [lattice]
    # An untouched lattice leaves the points where they are.
    np.testing.assert_allclose(scenes.deformScene(scene)["column"], points, rtol=0, atol=1e-12)
    scene.detachLattice("cage", "column")
    assert scene.latticesDeforming("column") == []
    scene.removeObject("column")
    assert scene.objectNames() == []


def test_scene_editing_errors_name_the_problem():
    scene = scenes.Scene()
    with pytest.raises(ffdkit.MeshIoError):
        scene.addMeshFile("nothing", "/nonexistent/mesh.ply")
    with pytest.raises(ValueError, match="up must be"):
        scene.addMeshFile("column", str(ROOT / "tests" / "data" / "y_up_column.obj"), up="x")
    with pytest.raises(ValueError):
        scene.attachNewLattice(["missing"])
    with pytest.raises(ValueError):
        scene.removeObject("missing")
