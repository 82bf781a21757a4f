"""Lattices both ways, measured per vertex against Blender's own Lattice modifier.

Blender -> ffdkit: for each interpolation (linear, cardinal, Catmull-Rom, B-spline, and mixed per
axis) and 1-6 points per axis, a rotated, scaled and moved Lattice object with moved points
deforms a rotated mesh whose points lie inside and outside it; Export Lattice writes a widget
file, and ffdkit-cli deform of the mesh's world points with it equals the modifier's result
within 1e-5 of the mesh's size.
ffdkit -> Blender: linear B-spline and two-point Bernstein box lattices with rotated, scaled
frames, and the exported files read back: Import ffdkit Lattices makes a Lattice object with a
Lattice modifier on the mesh whose result equals ffdkit-cli deform within 1e-5. Lattices Blender
cannot hold are refused, saying why."""

import os
import sys

import bpy
import mathutils
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_support as support  # noqa: E402

support.enable_addon()
import ffdkit  # noqa: E402

RELATIVE_TOLERANCE = 1e-5
folder = support.temporary_folder()
rng = np.random.default_rng(11)


def mesh_with_transform(points):
    obj = support.add_mesh("part", points)
    obj.rotation_euler = (0.2, -0.1, 0.5)
    obj.location = (0.1, -0.3, 0.2)
    obj.scale = (1.1, 0.9, 1.0)
    bpy.context.view_layer.update()
    return obj


def world(obj, local):
    matrix = np.array(obj.matrix_world)
    return local @ matrix[:3, :3].T + matrix[:3, 3]


def compare(obj, widget_file, label):
    """ffdkit-cli deform of the mesh's world points with the widget file vs the modifier's result."""
    rest = world(obj, support.vertices(obj))
    np.save(os.path.join(folder, "in.npy"), rest)
    out = os.path.join(folder, "out.npy")
    support.run_cli("deform", "-q", "-w", widget_file, os.path.join(folder, "in.npy"), "-o", out)
    expected = np.load(out)
    blender = world(obj, support.evaluated_points(obj))
    size = np.linalg.norm(rest.max(axis=0) - rest.min(axis=0))
    error = np.abs(blender - expected).max()
    moved = np.abs(blender - rest).max()
    print("%-58s moved %.3f  max |blender - ffdkit| %.2e (%.1e of the mesh's size)" % (label, moved, error, error / size))
    assert moved > 1e-2, "%s: nothing moved" % label
    assert error <= RELATIVE_TOLERANCE * size, "%s: Blender and ffdkit differ by %g" % (label, error)
    return error / size


def expect_error(operator, expected, **arguments):
    try:
        operator(**arguments)
    except RuntimeError as error:
        assert expected in str(error) and "Traceback" not in str(error), str(error)
        print("refused:", str(error).strip())
        return
    raise AssertionError("no error reported")


# ---- Blender -> ffdkit ------------------------------------------------------------------------
cases = [(kind, counts) for kind in ("KEY_LINEAR", "KEY_CARDINAL", "KEY_CATMULL_ROM", "KEY_BSPLINE")
         for counts in ((2, 2, 2), (3, 4, 5), (6, 2, 3), (4, 6, 6))]
cases += [(("KEY_CARDINAL", "KEY_LINEAR", "KEY_BSPLINE"), (5, 3, 4)), (("KEY_CATMULL_ROM",) * 3, (1, 4, 3))]
worst = {}
for kinds, counts in cases:
    kinds = (kinds,) * 3 if isinstance(kinds, str) else kinds
    support.empty_scene()
    data = bpy.data.lattices.new("cage")
    data.points_u, data.points_v, data.points_w = counts
    data.interpolation_type_u, data.interpolation_type_v, data.interpolation_type_w = kinds
    for point in data.points:
        point.co_deform = mathutils.Vector(point.co) + mathutils.Vector(rng.uniform(-0.3, 0.3, 3))
    cage = bpy.data.objects.new("cage", data)
    bpy.context.scene.collection.objects.link(cage)
    cage.location = (0.4, -0.2, 0.3)
    cage.rotation_euler = (0.3, -0.5, 0.9)
    cage.scale = (0.35, 0.6, 0.45)
    # Points inside the lattice and up to one lattice size beyond it on every side.
    half = 0.5 * np.maximum(np.array(counts) - 1, 1) * np.array(cage.scale)
    obj = mesh_with_transform(rng.uniform(-2.2, 2.2, (3000, 3)) * half.max())
    modifier = obj.modifiers.new("cage", "LATTICE")
    modifier.object = cage
    bpy.context.view_layer.objects.active = cage
    path = os.path.join(folder, "cage.json")
    assert bpy.ops.ffdkit.export_lattice(filepath=path) == {"FINISHED"}
    label = "to ffdkit: %s %s" % ("/".join(k[4:].lower() for k in kinds), "x".join(map(str, counts)))
    worst[label] = compare(obj, path, label)
    if counts == (4, 6, 6) or kinds[0] != kinds[1]:
        # ... and back: Import ffdkit Lattices gives the same deformation again.
        obj.modifiers.remove(modifier)
        bpy.context.view_layer.objects.active = obj
        assert bpy.ops.ffdkit.import_lattice(filepath=path) == {"FINISHED"}
        assert len(obj.modifiers) == 1 and obj.modifiers[0].object.type == "LATTICE"
        back = obj.modifiers[0].object.data
        assert (back.points_u, back.points_v, back.points_w) == counts
        assert (back.interpolation_type_u, back.interpolation_type_v, back.interpolation_type_w) == kinds
        worst["back: " + label] = compare(obj, path, "back from ffdkit: " + label[10:])

# ---- ffdkit -> Blender ------------------------------------------------------------------------
frame = np.eye(4)
frame[:3, :3] = np.array(mathutils.Euler((0.4, 0.1, -0.7)).to_matrix()) @ np.diag([1.6, 1.1, 0.8])
frame[:3, 3] = (-0.7, -0.5, -0.3)
for label, counts, basis, outside in (
        ("linear B-spline 3x2x4, clamp outside", (3, 2, 4), ffdkit.ffd.AxisBasis.bspline(1), ffdkit.ffd.OutsidePolicy.clampEdge()),
        ("linear B-spline 5x3x2, identity outside", (5, 3, 2), ffdkit.ffd.AxisBasis.bspline(1), ffdkit.ffd.OutsidePolicy.identity()),
        ("Bernstein 2x2x2, clamp outside", (2, 2, 2), ffdkit.ffd.AxisBasis.bernstein(), ffdkit.ffd.OutsidePolicy.clampEdge())):
    settings = ffdkit.widgets.LatticeSettings()
    settings.basis = [basis] * 3
    settings.outside = outside
    model = ffdkit.widgets.WidgetModel()
    lattice = model.addLattice(name="box", counts=counts, frame=frame, settings=settings)
    model.setControlPoints(lattice, np.asarray(model.restPoints(lattice)) + rng.uniform(-0.15, 0.15, (int(np.prod(counts)), 3)))
    path = os.path.join(folder, "box.json")
    ffdkit.scenes.writeWidgetFile(path, model)
    support.empty_scene()
    # Identity outside: Blender moves outside points, ffdkit does not, so the mesh stays inside.
    local = rng.uniform(0.02, 0.98, (3000, 3)) if outside == ffdkit.ffd.OutsidePolicy.identity() else rng.uniform(-0.4, 1.4, (3000, 3))
    points = local @ frame[:3, :3].T + frame[:3, 3]
    obj = support.add_mesh("part", points)
    bpy.ops.ffdkit.import_lattice(filepath=path)
    worst["to Blender: " + label] = compare(obj, path, "to Blender: " + label)

support.empty_scene()
obj = support.add_mesh("part", rng.uniform(0, 1, (50, 3)))
expect_error(bpy.ops.ffdkit.import_lattice, "Bernstein of degree",
             filepath=os.path.join(support.SOURCE_DIR, "widgets", "examples", "fig6-8.json"))
model = ffdkit.widgets.WidgetModel()
model.addLattice(name="cubic", counts=(4, 4, 4), settings=ffdkit.widgets.LatticeSettings())
settings = ffdkit.widgets.LatticeSettings()
settings.basis = [ffdkit.ffd.AxisBasis.bspline(3)] * 3
model.setLatticeSettings(model.find("cubic"), settings)
ffdkit.scenes.writeWidgetFile(os.path.join(folder, "cubic.json"), model)
expect_error(bpy.ops.ffdkit.import_lattice, "degree 3 on clamped uniform knots", filepath=os.path.join(folder, "cubic.json"))
expect_error(bpy.ops.ffdkit.import_lattice, "child lattices",
             filepath=os.path.join(support.SOURCE_DIR, "widgets", "examples", "fig6-9.json"))
assert len(obj.modifiers) == 0 and not [o for o in bpy.data.objects if o.type == "LATTICE"]
bpy.context.view_layer.objects.active = obj
expect_error(bpy.ops.ffdkit.export_lattice, "select a Lattice object", filepath=os.path.join(folder, "none.json"))
print("worst relative error: %.2e (%s)" % max((v, k) for k, v in worst.items()))
