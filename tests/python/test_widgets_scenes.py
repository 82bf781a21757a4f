"""ffdkit.widgets and ffdkit.scenes from Python: building and driving widget models, widget
and scene files, the scene deformer, mesh files and generators, with their errors."""

import math
import pathlib

import numpy as np
import pytest

import ffdkit
from ffdkit import ffd, scenes, widgets
from reference import rotation

ROOT = pathlib.Path(__file__).resolve().parents[2]


def readme_model():
    """The README's scripting example: a knob on the top slab turning a push on a side face."""
    model = widgets.WidgetModel()
    box = model.addLattice("box", (3, 3, 3))
    top = model.addCell(box, widgets.CellSpec.slab(2, 2), "top")
    knob = model.addAffine(top, widgets.AffineKind.Rotate, "knob")
    side = model.addCell(box, widgets.CellSpec.face(0, 0, 0, 0), "side")
    push = model.addAffine(side, widgets.AffineKind.Translate, "push")
    model.bind(knob, push, widgets.ConversionRule(0.1))
    return model


# ---- widget model -----------------------------------------------------------------------------------
def test_build_list_and_find_widgets_by_name():
    model = readme_model()
    assert model.names() == ["box", "top", "knob", "side", "push"]
    assert model.names(widgets.WidgetType.Affine) == ["knob", "push"]
    box = model.find("box")
    assert model.type(box) == widgets.WidgetType.Lattice and tuple(model.counts(box)) == (3, 3, 3)
    assert repr(box) == "w0"
    [binding] = [model.binding(b) for b in model.bindings() if model.binding(b).kind == widgets.BindingKind.Variation]
    assert binding.rule.gain == 0.1 and binding.from_ == model.find("knob") and binding.to == model.find("push")


def test_a_variation_driven_as_a_gesture_moves_the_bound_widgets():
    model = readme_model()
    knob, push, box = model.find("knob"), model.find("push"), model.find("box")
    model.beginGesture(knob)
    model.updateGesture(0.3)
    model.updateGesture(math.pi / 2)  # relative to the gesture start: no drift
    assert model.gestureActive()
    model.endGesture()
    assert model.variation(knob) == pytest.approx(math.pi / 2)
    assert model.variation(push) == pytest.approx(0.1 * math.pi / 2)
    moved = model.controlPoints(box) - model.restPoints(box)
    # The side face's four points translate together by 0.1 * pi/2 ...
    side = model.cellIndices(model.find("side"))
    np.testing.assert_allclose(np.linalg.norm(moved[side], axis=1), 0.1 * math.pi / 2, rtol=1e-12)
    np.testing.assert_allclose(moved[side] - moved[side][0], 0.0, atol=1e-14)
    # ... and the top slab turns a quarter about its centroid's z axis.
    top = model.cellIndices(model.find("top"))
    rest = model.restPoints(box)[top]
    centre = rest.mean(axis=0)
    turned = model.controlPoints(box)[top]
    candidates = [(rest - centre) @ rotation(2, a).T + centre for a in (90.0, -90.0)]
    assert min(np.abs(turned - c).max() for c in candidates) < 1e-12
    untouched = np.setdiff1d(np.arange(27), np.concatenate([side, top]))
    np.testing.assert_array_equal(moved[untouched], 0.0)


def test_widget_errors_are_python_exceptions_with_the_cpp_message():
    model = readme_model()
    with pytest.raises(ffdkit.WidgetError, match="nope") as error:
        model.find("nope")
    assert error.value.code == "UnknownWidget"
    with pytest.raises(ffdkit.WidgetError) as error:
        model.endGesture()
    assert error.value.code == "GestureState"
    with pytest.raises(ffdkit.WidgetError) as error:
        model.bind(model.find("knob"), model.find("knob"))
    assert error.value.code == "InvalidBinding"


def test_widget_files_round_trip_byte_for_byte(tmp_path):
    for path in sorted((ROOT / "widgets" / "examples").glob("*.json")):
        model = scenes.readWidgetFile(path)
        assert scenes.widgetFileText(model) == path.read_text()
        copy = tmp_path / path.name
        scenes.writeWidgetFile(copy, model)
        assert copy.read_bytes() == path.read_bytes()
    model = readme_model()
    model.applyVariation(model.find("knob"), 1.0)
    scenes.writeWidgetFile(tmp_path / "tool.json", model)
    loaded = scenes.readWidgetFile(tmp_path / "tool.json")
    box = loaded.find("box")
    np.testing.assert_array_equal(loaded.controlPoints(box), model.controlPoints(model.find("box")))
    (tmp_path / "bad.json").write_text('{"format": "ffdkit-widgets",\n "version": }')
    with pytest.raises(ffdkit.WidgetFileError, match=r"bad.json:2:"):
        scenes.readWidgetFile(tmp_path / "bad.json")


def test_ffd_lattice_of_a_widget_deforms_like_the_model_says():
    model = readme_model()
    model.applyVariation(model.find("knob"), 0.7)
    lattice = model.ffdLattice(model.find("box"))
    np.testing.assert_array_equal(lattice.controlPoints, model.controlPoints(model.find("box")))
    points = np.random.default_rng(3).random((100, 3))
    out = ffd.deformPoints(lattice, points)
    np.testing.assert_allclose(out, lattice.evaluate(ffd.embed(lattice, points).parameters()), atol=1e-12)


# ---- scenes --------------------------------------------------------------------------------------------
def press_expectation(scene, press):
    """The press lattice is trilinear (2x2x2 Bernstein) on the unit box with its top face lowered
    by the press distance: a block point (x, y, z) goes to (x, y, z (1 - press))."""
    block = scene.findObject("block").mesh.points
    return block * np.array([1.0, 1.0, 1.0 - press])


def test_scene_load_drive_and_deformed_points():
    scene = scenes.readScene(ROOT / "scenes" / "examples" / "press")
    assert scene.objectNames() == ["block"]
    assert [a.lattice for a in scene.attachments] == [scene.widgets.find("press-frame")]
    model = scene.widgets
    handle, press = model.find("handle"), model.find("press")
    model.setVariation(handle, 1.5 * math.pi)  # 0.4 per turn: 0.3, the clamp's end
    assert model.variation(press) == pytest.approx(0.3)
    deformer = scenes.SceneDeformer()
    deformer.update(scene)
    np.testing.assert_allclose(deformer.points("block"), press_expectation(scene, 0.3), atol=1e-12)
    model.setVariation(handle, 4 * math.pi)  # clamped at 0.3
    deformer.update(scene)
    np.testing.assert_allclose(deformer.points("block"), press_expectation(scene, 0.3), atol=1e-12)
    np.testing.assert_array_equal(scenes.deformScene(scene)["block"], deformer.points("block"))
    with pytest.raises(ValueError, match="nothing"):
        deformer.points("nothing")


def test_objects_are_held_by_id_and_evaluate_runs_once_per_change():
    scene = scenes.readScene(ROOT / "scenes" / "examples" / "press")
    block = scene.objectId("block")
    assert scene.findObject("block").id == block and scene.objectName(block) == "block"
    assert scene.attachments[0].objects == [block]
    deformer = scenes.SceneDeformer()
    assert deformer.evaluate(scene)
    assert not deformer.evaluate(scene)  # nothing changed
    embedded = deformer.lastStats.reembeddedStages
    assert embedded > 0
    model = scene.widgets
    model.setVariation(model.find("handle"), 1.5 * math.pi)
    assert deformer.evaluate(scene)
    assert deformer.lastStats.reembeddedStages == 0
    np.testing.assert_allclose(deformer.points("block"), press_expectation(scene, 0.3), atol=1e-12)


def test_scene_deformer_gesture_steps_move_by_deltas_and_finish_exactly():
    scene = scenes.readScene(ROOT / "scenes" / "examples" / "press")
    model = scene.widgets
    lattice = model.find("press-frame")
    deformer = scenes.SceneDeformer()
    deformer.update(scene)
    base = np.array(deformer.points("block"))
    base_revision = deformer.revision("block")
    assert deformer.gestureMotion("block") is None
    control = np.array(model.controlPoints(lattice))
    moved = len(control) - 1  # a top corner of the 2x2x2 press lattice
    linear = np.asarray(model.latticeFrame(lattice))[:3, :3]
    for step in range(1, 4):
        control[moved] += [0.01, 0.0, -0.02]
        model.setControlPoints(lattice, control)
        deformer.updateGesture(scene, lattice)
        assert deformer.lastStats.deltaStages == 1
        assert deformer.revision("block") == base_revision + step
        motion = deformer.gestureMotion("block")
        assert motion.baseRevision == base_revision and motion.lattice == lattice
        assert motion.controlPoints == [moved]
        np.testing.assert_allclose(motion.displacements[0], linear @ [0.01 * step, 0.0, -0.02 * step], atol=1e-15)
        # Linear in the moved control point: base + weight * displacement (trilinear weights here).
        weights = deformer.controlWeights("block", moved)
        assert weights.shape == (len(base),) and weights.min() >= 0.0 and weights.max() <= 1.0
        followed = base + np.outer(weights, motion.displacements[0])
        np.testing.assert_allclose(deformer.points("block"), followed, rtol=0, atol=1e-13)
    deformer.finishGesture(scene)
    assert deformer.gestureMotion("block") is None
    np.testing.assert_array_equal(deformer.points("block"), scenes.deformScene(scene)["block"])
    with pytest.raises(ffdkit.LatticeError):
        deformer.controlWeights("block", len(control))


def test_scene_files_round_trip_and_report_errors(tmp_path):
    source = ROOT / "scenes" / "examples" / "hierarchy" / "scene.json"
    scene = scenes.readScene(source)
    assert scenes.sceneFileText(scene) == source.read_text()
    scenes.writeScene(tmp_path / "scene.json", scene)
    assert (tmp_path / "scene.json").read_text() == source.read_text()
    with pytest.raises(ffdkit.SceneFileError, match="missing.json"):
        scenes.readScene(tmp_path / "missing.json")


def test_scene_deformer_progress_and_cancel():
    scene = scenes.readScene(ROOT / "scenes" / "examples" / "cylinder-twist")
    fractions = []
    deformer = scenes.SceneDeformer()
    deformer.setProgress(lambda f: False)
    with pytest.raises(ffdkit.Cancelled):
        deformer.update(scene)
    deformer.setProgress(fractions.append)
    deformer.update(scene)
    assert fractions[0] == 0.0 and fractions[-1] == 1.0 and fractions == sorted(fractions)
    reference = scenes.deformScene(scene)
    for name in scene.objectNames():
        np.testing.assert_array_equal(deformer.points(name), reference[name])


# ---- meshes and generators ----------------------------------------------------------------------------
def test_mesh_write_and_read_round_trip(tmp_path):
    points = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.25, 0.125, 1.0 / 3.0]])
    triangles = np.array([[0, 1, 2], [0, 1, 3]])
    mesh = scenes.MeshData(points, triangles)
    for name in ("mesh.obj", "mesh.vtp", "mesh.ply"):
        scenes.writeMesh(tmp_path / name, mesh)
        back = scenes.readMesh(tmp_path / name)
        np.testing.assert_allclose(back.points, points, rtol=1e-7)
        np.testing.assert_array_equal(back.triangles, triangles)
    scenes.writeMesh(tmp_path / "points.xyz", scenes.MeshData(points))
    np.testing.assert_array_equal(scenes.readMesh(tmp_path / "points.xyz").points, points)
    with pytest.raises(ffdkit.MeshIoError, match="nothing.obj"):
        scenes.readMesh(tmp_path / "nothing.obj")
    with pytest.raises(ffdkit.MeshIoError):
        scenes.writeMesh(tmp_path / "bad.obj", scenes.MeshData(points, np.array([[0, 1, 9]])))


def test_generators_by_name_with_parameters():
    names = scenes.generatorNames()
    assert "qi-interpolate" in names and len(names) >= 10
    assert "points" in scenes.generatorParameterNames("qi-interpolate")
    data = np.array([[0, 3, 0], [1, 2.8, 0.3], [1.8, 2.2, 0.9], [2.2, 1.3, 1.2]])
    curve = scenes.generate("qi-interpolate", {"points": data})
    assert curve.segments.shape[0] == curve.points.shape[0] - 1 and curve.triangles.shape[0] == 0
    # An interpolating curve starts and ends at its end points and passes through the others:
    # they lie on the sampled polyline up to its chord error (~h^2 curvature / 8, h ~ 0.01).
    np.testing.assert_allclose(curve.points[[0, -1]], data[[0, -1]], atol=1e-12)
    a, b = curve.points[curve.segments[:, 0]], curve.points[curve.segments[:, 1]]
    for p in data[1:-1]:
        s = np.clip(np.einsum("ij,ij->i", p - a, b - a) / np.einsum("ij,ij->i", b - a, b - a), 0, 1)
        assert np.linalg.norm(a + s[:, None] * (b - a) - p, axis=1).min() < 1e-4
    finer = scenes.generate("qi-interpolate", {"points": data.tolist()}, density=2.0)
    assert finer.points.shape[0] > curve.points.shape[0]
    with pytest.raises(ffdkit.GeneratorError, match="colour"):
        scenes.generate("qi-interpolate", {"points": data, "colour": 1})
    with pytest.raises(ffdkit.GeneratorError, match="no-such"):
        scenes.generate("no-such", {})
