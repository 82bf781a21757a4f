"""ffdkit.app.Document: a scene edited as the app edits it, one undoable command per operation,
checked against the same edits made directly on a copy of the scene (scenes.deformScene)."""

import math
import pathlib

import numpy as np
import pytest

from ffdkit import app, scenes, widgets

ROOT = pathlib.Path(__file__).resolve().parents[2]
PRESS = ROOT / "scenes" / "examples" / "press"


def deformed_directly(scene, edit):
    """The objects' points after `edit(model)` on a copy of `scene`, without the Document."""
    copy = scenes.readScene(PRESS) if scene is None else scene
    edit(copy.widgets)
    return scenes.deformScene(copy)


def test_an_operation_deforms_the_objects_and_undo_redo_restore_them_exactly():
    doc = app.Document(scenes.readScene(PRESS))
    handle = doc.scene.widgets.find("handle")
    before = doc.points("block")
    np.testing.assert_array_equal(before, scenes.deformScene(scenes.readScene(PRESS))["block"])
    assert not doc.canUndo
    turned = doc.scene.widgets.variation(handle) + math.pi  # half a turn more: 0.2 down
    doc.setVariation(handle, turned)
    expected = deformed_directly(None, lambda model: model.setVariation(handle, turned))["block"]
    np.testing.assert_allclose(doc.points("block"), expected, rtol=0, atol=1e-12)
    assert np.abs(doc.points("block") - before).max() > 0.05  # the press moved
    assert doc.canUndo and "handle" in doc.undoDescription
    doc.undo()
    np.testing.assert_array_equal(doc.points("block"), before)
    assert doc.canRedo and not doc.canUndo
    doc.redo()
    np.testing.assert_allclose(doc.points("block"), expected, rtol=0, atol=1e-12)


def test_consecutive_values_of_one_variation_are_one_undo_step():
    doc = app.Document(scenes.readScene(PRESS))
    handle = doc.scene.widgets.find("handle")
    start = doc.scene.widgets.variation(handle)
    for value in (0.5, 1.0, 1.5, 2.0):  # a mouse wheel, a typed number
        doc.setVariation(handle, value)
    assert doc.undoSteps == 1
    doc.undo()
    assert doc.scene.widgets.variation(handle) == start


def test_a_tool_built_step_by_step_undoes_step_by_step():
    doc = app.Document(scenes.Scene())
    doc.addMeshFile("column", str(ROOT / "tests" / "data" / "y_up_column.obj"), up="y")
    rest = doc.points("column")
    lattice = doc.newLattice(counts=(3, 3, 3))
    doc.attachLattice(lattice, "column")
    top = doc.addCell(lattice, widgets.CellSpec.slab(2, 2))
    lift = doc.addAffine(top, widgets.AffineKind.Translate)
    doc.setVariation(lift, 0.3)
    assert doc.undoSteps == 6
    lifted = doc.points("column")
    # The top of the column moves with the top slab; its bottom, near the bottom slab that stays,
    # moves far less (Bernstein bases: every point feels every control point a little).
    z = rest[:, 2]
    moved = np.linalg.norm(lifted - rest, axis=1)
    assert moved[z == z.max()].min() > 0.05
    assert moved[z == z.min()].max() < 0.1 * moved[z == z.max()].min()
    names = []
    while doc.canUndo:
        names.append(doc.undoDescription)
        doc.undo()
    assert len(names) == 6
    assert doc.scene.objectNames() == [] and doc.scene.widgets.names() == []
    while doc.canRedo:
        doc.redo()
    np.testing.assert_allclose(doc.points("column"), lifted, rtol=0, atol=1e-12)


def test_the_history_holds_deltas_not_copies():
    doc = app.Document(scenes.readScene(PRESS))
    handle = doc.scene.widgets.find("handle")
    doc.setVariation(handle, 1.0)
    mesh_bytes = sum(doc.scene.findObject(n).mesh.points.nbytes for n in doc.scene.objectNames())
    assert 0 < doc.undoBytes < mesh_bytes


def test_errors_leave_no_trace():
    doc = app.Document(scenes.readScene(PRESS))
    steps = doc.undoSteps
    with pytest.raises(ValueError):
        doc.attachLattice(doc.scene.widgets.find("handle"), "block")  # not a lattice
    with pytest.raises(ValueError):
        doc.removeObjects(["missing"])
    with pytest.raises(ValueError, match="up must be 'z' or 'y', got 'x'"):
        doc.addMeshFile("column", str(ROOT / "tests" / "data" / "y_up_column.obj"), up="x")
    with pytest.raises(ValueError, match="nothing to undo"):
        doc.undo()
    assert doc.undoSteps == steps
