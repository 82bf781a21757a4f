"""ffdkit.ffd.ShapeConstraints, checkFolding and ffdkit.pygem's CFFD / BFFD / VFFD against
independent numpy computations (divergence-theorem volume, least-norm solves by numpy.linalg)."""

import numpy as np
import pytest

from ffdkit import ConstraintError, ffd
from ffdkit.pygem import BFFD, CFFD, FFD, VFFD
from ffdkit.pygem_cffd import _volume


def sphere(rings=20, radius=0.3, centre=(0.5, 0.5, 0.5)):
    """A closed UV sphere: points (n, 3), outward triangles (t, 3)."""
    segments = 2 * rings
    points = [np.array(centre) + [0, 0, radius]]
    for r in range(1, rings):
        theta = np.pi * r / rings
        for s in range(segments):
            phi = 2 * np.pi * s / segments
            points.append(np.array(centre) + radius * np.array(
                [np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)]))
    points.append(np.array(centre) - [0, 0, radius])
    n = len(points)

    def at(ring, s):
        return 1 + (ring - 1) * segments + s % segments

    tris = [(0, at(1, s), at(1, s + 1)) for s in range(segments)]
    for r in range(1, rings - 1):
        for s in range(segments):
            tris += [(at(r, s), at(r + 1, s), at(r + 1, s + 1)), (at(r, s), at(r + 1, s + 1), at(r, s + 1))]
    tris += [(n - 1, at(rings - 1, s + 1), at(rings - 1, s)) for s in range(segments)]
    return np.array(points), np.array(tris)


def divergence_volume(points, triangles):
    a, b, c = points[triangles[:, 0]], points[triangles[:, 1]], points[triangles[:, 2]]
    return np.sum(np.einsum("ij,ij->i", a, np.cross(b, c))) / 6.0


def test_enclosed_volume_matches_numpy_and_open_surfaces_are_refused():
    points, triangles = sphere()
    assert ffd.enclosedVolume(points, triangles) == pytest.approx(divergence_volume(points, triangles), rel=1e-14)
    with pytest.raises(ConstraintError, match="open"):
        ffd.enclosedVolume(points, triangles[:-1])
    with pytest.raises(ValueError):  # ConstraintError is a ValueError
        ffd.enclosedVolume(points, triangles[:-1])


def test_keep_volume_after_a_drag_to_1e12():
    points, triangles = sphere()
    lattice = ffd.makeBoxLattice(counts=(4, 4, 4))
    rest = divergence_volume(points, triangles)
    constraints = ffd.ShapeConstraints(lattice, points)
    constraints.keepVolume(triangles, rest)
    for step in range(5):  # five drag steps, each followed by the volume solve
        lattice.controlPoints[lattice.index(2, 1, 2)] += [0.03, 0.01, -0.02]
        result = constraints.solve(lattice)
        lattice.setControlPoints(lattice.controlPoints + result.change)
        deformed = ffd.deformPoints(lattice, points)
        assert abs(divergence_volume(deformed, triangles) - rest) / rest <= 1e-12
        assert result.volumeRelativeError <= 1e-12
    assert result.iterations >= 1


def test_linear_rows_match_numpys_least_norm_solve():
    rng = np.random.default_rng(3)
    lattice = ffd.makeBoxLattice(counts=(3, 4, 3))
    points = 0.1 + 0.8 * rng.random((40, 3))
    A = rng.random((4, points.size))
    x0 = ffd.deformPoints(lattice, points)
    b = A @ x0.reshape(-1) + 0.05 * rng.random(4)
    constraints = ffd.ShapeConstraints(lattice, points)
    constraints.addLinear(A, b)
    change = constraints.solve(lattice).change
    # Independent: the deformation matrix M from unit moves through deformPoints, then J^+ r.
    N = lattice.pointCount
    M = np.zeros((points.size, 3 * N))
    for k in range(3 * N):
        moved = lattice.copy()
        moved.controlPoints[k // 3, k % 3] += 1.0
        M[:, k] = (ffd.deformPoints(moved, points) - x0).reshape(-1)
    expected = np.linalg.lstsq(A @ M, b - A @ x0.reshape(-1), rcond=None)[0]
    assert np.max(np.abs(change.reshape(-1) - expected)) < 1e-10
    lattice.setControlPoints(lattice.controlPoints + change)
    assert np.max(np.abs(A @ ffd.deformPoints(lattice, points).reshape(-1) - b)) < 1e-11


def test_barycentre_with_fixed_axes():
    rng = np.random.default_rng(4)
    lattice = ffd.makeBoxLattice(counts=(4, 4, 4))
    points = 0.1 + 0.8 * rng.random((300, 3))
    constraints = ffd.ShapeConstraints(lattice, points)
    free = np.zeros((lattice.pointCount, 3), dtype=bool)
    free[:, 1] = True
    constraints.setFreeControls(free)
    target = points.mean(axis=0) + [0.0, 0.04, 0.0]
    constraints.keepBarycentre(target)
    change = constraints.solve(lattice).change
    assert np.all(change[:, [0, 2]] == 0.0)
    lattice.setControlPoints(lattice.controlPoints + change)
    assert np.allclose(ffd.deformPoints(lattice, points).mean(axis=0), target, atol=1e-13, rtol=0)
    # Unreachable: the x mean with only y free.
    constraints.keepBarycentre(points.mean(axis=0) + [0.01, 0.0, 0.0])
    with pytest.raises(ConstraintError, match="cannot be met"):
        constraints.solve(lattice)


def test_fold_check_catches_a_fold_and_certifies_a_bend():
    lattice = ffd.makeBoxLattice(counts=(4, 4, 4))
    assert ffd.checkFolding(lattice).certifiedPositive()
    for j in (1, 2):
        for k in (1, 2):
            lattice.controlPoints[lattice.index(1, j, k), 0] += 3.0
    result = ffd.checkFolding(lattice)
    assert result.cells == ["folds"]
    assert np.linalg.det(lattice.jacobian(result.witness[0])) <= 1e-12
    # The determinant against central differences of the evaluator.
    uvw = np.array([0.3, 0.6, 0.45])
    h = 1e-6
    J = np.column_stack([np.ravel(lattice.evaluate(uvw + h * e) - lattice.evaluate(uvw - h * e)) / (2 * h)
                         for e in np.eye(3)])
    assert ffd.jacobianDeterminant(lattice, uvw) == pytest.approx(np.linalg.det(J), rel=1e-6)


def test_vffd_meets_the_volume_exactly_and_splits_it_over_the_axes_as_pygem():
    points, triangles = sphere(rings=12)
    b = _volume(points, triangles) * 1.05
    vffd = VFFD(triangles, b, [3, 3, 3])
    vffd.adjust_control_points(points)
    assert abs(vffd.fun(vffd(points))[0] - b[0]) / b[0] <= 1e-12
    # Each axis moved only its own weights (PyGeM's per-axis split) and all three moved.
    for mu in (vffd.array_mu_x, vffd.array_mu_y, vffd.array_mu_z):
        assert np.max(np.abs(mu)) > 0


def test_cffd_is_pygems_per_axis_least_norm_solve():
    rng = np.random.default_rng(0)
    points = rng.random((50, 3))
    A = rng.random((2, points.size))

    def fun(x):
        return A @ x.reshape(-1)

    b = fun(points) + 0.01
    cffd = CFFD(b, fun, [2, 2, 2])
    cffd.adjust_control_points(points)
    assert np.allclose(fun(cffd.ffd(points)), b, rtol=1e-12, atol=0)
    # Independent: PyGeM's algorithm with exact linear maps. Axis a closes a third of the gap
    # with the least-norm change of the axis-a weights.
    ref = FFD([2, 2, 2])
    gap = b - fun(ref(points))
    for axis in range(3):
        base = fun(ref(points))
        target = base + gap / 3
        weights = [ref.array_mu_x, ref.array_mu_y, ref.array_mu_z][axis]
        J = np.zeros((2, weights.size))
        for k in range(weights.size):
            weights.reshape(-1)[k] += 1.0
            J[:, k] = fun(ref(points)) - base
            weights.reshape(-1)[k] -= 1.0
        weights += np.linalg.lstsq(J, target - base, rcond=None)[0].reshape(weights.shape)
    for ours, expected in zip((cffd.array_mu_x, cffd.array_mu_y, cffd.array_mu_z),
                              (ref.array_mu_x, ref.array_mu_y, ref.array_mu_z)):
        assert np.allclose(ours, expected, atol=1e-9, rtol=0)


def test_bffd_keeps_the_mean():
    rng = np.random.default_rng(1)
    points = rng.random((80, 3))
    target = points.mean(axis=0) + [0.01, -0.02, 0.005]
    bffd = BFFD(target, [3, 2, 2])
    bffd.adjust_control_points(points)
    assert np.allclose(bffd.ffd(points).mean(axis=0), target, atol=1e-13, rtol=0)
