"""The exact B-spline form of Blender's lattice (ffdkit_blender/lattice_convert.py) against an
independent evaluation of Blender's Lattice modifier in double precision: the loop of
lattice_deform.cc (four weights per axis from key.cc's key_curve_position_weights on the points
floor(u)-1 .. floor(u)+2, indices clamped to the lattice), written out here. Runs without Blender
(pytest); the float32 comparison with Blender itself is blender_lattice_convert."""

import importlib.util
import os

import numpy as np
import pytest

import ffdkit

_here = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location(
    "lattice_convert", os.path.join(_here, "..", "..", "blender", "ffdkit_blender", "lattice_convert.py"))
lattice_convert = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(lattice_convert)

F32 = lambda x: float(np.float32(x))  # noqa: E731  Blender's constants are float literals


def key_weights(t, kind):
    """key.cc's key_curve_position_weights, term by term."""
    t2, t3 = t * t, t * t * t
    if kind == "KEY_LINEAR":
        return [0.0, 1.0 - t, t, 0.0]
    if kind in ("KEY_CARDINAL", "KEY_CATMULL_ROM"):
        fc = F32(0.71) if kind == "KEY_CARDINAL" else 0.5
        return [-fc * t3 + 2.0 * fc * t2 - fc * t,
                (2.0 - fc) * t3 + (fc - 3.0) * t2 + 1.0,
                (fc - 2.0) * t3 + (3.0 - 2.0 * fc) * t2 + fc * t,
                fc * t3 - fc * t2]
    s, w = F32(0.16666666), F32(0.66666666)
    return [-s * t3 + 0.5 * t2 - 0.5 * t + s, 0.5 * t3 - t2 + w, -0.5 * t3 + 0.5 * t2 + 0.5 * t + s, s * t3]


def blender_deform(points, counts, kinds, origin, spacing, lattice_points):
    """lattice_deform.cc's BKE_lattice_deform_data_eval_co in lattice space, float64."""
    grid = np.stack(np.meshgrid(*[origin[a] + spacing[a] * np.arange(counts[a]) for a in (2, 1, 0)][::-1],
                                indexing="ij"), axis=-1)  # [u, v, w, xyz]
    deltas = lattice_points.reshape(counts[2], counts[1], counts[0], 3).transpose(2, 1, 0, 3) - grid
    out = points.copy()
    for p, x in enumerate(points):
        weights, first = [], []
        for a in range(3):
            if counts[a] > 1:
                u = (x[a] - origin[a]) / spacing[a]
                i = int(np.floor(u))
                weights.append(key_weights(u - i, kinds[a]))
                first.append(i - 1)
            else:
                weights.append([0.0, 1.0, 0.0, 0.0])
                first.append(-1)
        for r in range(4):
            for s in range(4):
                for q in range(4):
                    w = weights[0][r] * weights[1][s] * weights[2][q]
                    if w != 0.0:
                        i = [min(max(first[0] + r, 0), counts[0] - 1), min(max(first[1] + s, 0), counts[1] - 1),
                             min(max(first[2] + q, 0), counts[2] - 1)]
                        out[p] += w * deltas[i[0], i[1], i[2]]
    return out


CASES = [(kind, counts) for kind in lattice_convert.KINDS for counts in ((2, 2, 2), (3, 5, 4), (6, 1, 3))]
CASES += [(("KEY_BSPLINE", "KEY_CARDINAL", "KEY_LINEAR"), (4, 3, 5))]


@pytest.mark.parametrize("kinds,counts", CASES)
def test_exported_lattice_deforms_as_blenders_formula(kinds, counts):
    kinds = (kinds,) * 3 if isinstance(kinds, str) else kinds
    rng = np.random.default_rng(sum(counts))
    origin = np.array([-0.5 * (n - 1) for n in counts]) * 0.7
    spacing = np.array([0.7, 0.7, 0.7])
    grid = np.stack(np.meshgrid(*[origin[a] + spacing[a] * np.arange(counts[a]) for a in range(3)], indexing="ij"),
                    axis=-1).transpose(2, 1, 0, 3).reshape(-1, 3)  # u fastest
    lattice_points = grid + rng.uniform(-0.25, 0.25, grid.shape)
    extent = np.maximum(np.array(counts) - 1, 1) * spacing
    points = rng.uniform(-1, 1, (400, 3)) * extent  # inside and up to a lattice size outside
    model = lattice_convert.widget_model_from_blender(ffdkit, "cage", counts, kinds, origin, spacing,
                                                      lattice_points, np.eye(4))
    ffdkit_points = ffdkit.ffd.deformPoints(model.ffdLattice(model.roots()[0]), points)
    expected = blender_deform(points, counts, kinds, origin, spacing, lattice_points)
    assert np.abs(expected - points).max() > 1e-2
    # Blender's B-spline weights, with the float constants 0.16666666 and 0.66666666, sum to
    # 1 - 3e-8 and jump by that much of a move at each grid plane; the exported spline is
    # continuous. The other interpolations are continuous as Blender writes them: exact.
    moves = np.abs(lattice_points - grid).max()
    tolerance = 1e-7 * moves if "KEY_BSPLINE" in kinds else 1e-12 * max(1.0, np.abs(expected).max())
    assert np.abs(ffdkit_points - expected).max() <= tolerance


def test_kinds_round_trip_through_the_widget_file():
    counts, kinds = (3, 4, 2), ("KEY_CARDINAL", "KEY_CATMULL_ROM", "KEY_BSPLINE")
    origin, spacing = lattice_convert.blender_grid(counts)
    grid = lattice_convert._grid(*(origin[a] + spacing[a] * np.arange(counts[a]) for a in range(3)))
    moved = grid + np.random.default_rng(4).uniform(-0.2, 0.2, grid.shape)
    model = lattice_convert.widget_model_from_blender(ffdkit, "cage", counts, kinds, origin, spacing, moved, np.eye(4))
    back = lattice_convert.blender_lattice_from_model(ffdkit, model, model.roots()[0])
    assert back.kinds == list(kinds) and back.counts == list(counts)
    assert np.abs(back.points - moved).max() < 1e-12
