"""ffdkit.ffd from Python: lattices, embedding, deformation, pipelines, direct manipulation,
numpy round trips, errors, progress and cancel, and the GIL released during long work."""

import threading
import time

import numpy as np
import pytest

import ffdkit
from ffdkit import ffd
from reference import apply_frame, bernstein, bernstein_ffd, rotation

RNG = np.random.default_rng(20261125)


def bernstein_box(counts=(4, 3, 5), frame=None, policy=None):
    return ffd.makeBoxLattice(counts=counts, bases=ffd.AxisBasis.bernstein(), frame=frame,
                              outsidePolicy=policy or ffd.OutsidePolicy.identity())


def oriented_frame():
    frame = np.eye(4)
    frame[:3, :3] = rotation(0, 25.0) @ rotation(2, -40.0) @ np.diag([2.0, 0.5, 1.5])
    frame[:3, 3] = [0.3, -1.0, 2.0]
    return frame


# ---- lattices ---------------------------------------------------------------------------------
def test_box_lattice_counts_bases_knots_and_rest_grid():
    lattice = ffd.makeBoxLattice(counts=(4, 3, 2), bases=[ffd.AxisBasis.bernstein(), ffd.AxisBasis.bspline(1),
                                                          ffd.AxisBasis.bspline(3)])
    assert tuple(lattice.counts) == (4, 3, 2)
    assert lattice.pointCount == 24
    assert lattice.basis(0).kind == ffd.AxisBasis.Kind.Bernstein
    assert lattice.degree(0) == 3 and lattice.degree(1) == 1 and lattice.degree(2) == 1  # cubic capped to count-1
    np.testing.assert_array_equal(lattice.knots(0), [0, 0, 0, 0, 1, 1, 1, 1])
    np.testing.assert_array_equal(lattice.knots(1), [0, 0, 0.5, 1, 1])
    # Rest points at the Greville abscissae of a unit box: i/(count-1) here, i fastest.
    rest = lattice.restPoints
    assert rest.shape == (24, 3)
    for flat in range(24):
        i, j, k = lattice.gridIndex(flat)
        assert lattice.index(i, j, k) == flat
        np.testing.assert_allclose(rest[flat], [i / 3, j / 2, k / 1], atol=1e-15)
    assert lattice.restIsAffine


def test_control_points_are_a_writable_view_of_the_lattice():
    lattice = bernstein_box((3, 3, 3))
    view = lattice.controlPoints
    assert view.shape == (27, 3) and view.dtype == np.float64 and view.flags.writeable
    revision = lattice.revision
    view[13] += [0.1, -0.2, 0.3]  # the centre point
    assert np.shares_memory(view, lattice.controlPoints)
    # The lattice sees the edit: X at the centre moves by B_1(1/2)^3 * the displacement.
    weight = bernstein(2, 0.5)[1] ** 3
    np.testing.assert_allclose(lattice.evaluate([[0.5, 0.5, 0.5]])[0],
                               [0.5 + 0.1 * weight, 0.5 - 0.2 * weight, 0.5 + 0.3 * weight], rtol=1e-14)
    assert lattice.revision != revision
    lattice.resetToRest()
    np.testing.assert_array_equal(lattice.controlPoints, lattice.restPoints)
    with pytest.raises(ValueError):
        lattice.restPoints[0, 0] = 5.0  # read-only


def test_non_finite_control_points_written_through_the_view_are_refused():
    lattice = bernstein_box((2, 2, 2))
    lattice.controlPoints[3, 1] = np.nan
    with pytest.raises(ffdkit.LatticeError, match="not finite"):
        lattice.evaluate([[0.5, 0.5, 0.5]])


def test_frame_round_trip_and_world_mapping():
    frame = oriented_frame()
    lattice = bernstein_box((3, 4, 2), frame=frame)
    np.testing.assert_allclose(lattice.frame, frame, rtol=0, atol=1e-15)
    moved = frame.copy()
    moved[:3, 3] += [1.0, 2.0, 3.0]
    lattice.frame = moved
    np.testing.assert_allclose(lattice.frame[:3, 3], moved[:3, 3])
    with pytest.raises(ValueError, match="last row"):
        lattice.setFrame(np.ones((4, 4)))
    with pytest.raises(ValueError, match="4 x 4"):
        lattice.setFrame(np.eye(3))


def test_user_shaped_lattice_evaluates_its_own_control_points():
    counts = (3, 2, 2)
    base = ffd.makeBoxLattice(counts=counts, bases=ffd.AxisBasis.bernstein()).restPoints.copy()
    bent = base + 0.05 * np.sin(7 * base)  # a non-affine rest shape
    lattice = ffd.makeLattice(counts, ffd.AxisBasis.bernstein(), bent)
    assert not lattice.restIsAffine
    uvw = RNG.random((50, 3))
    np.testing.assert_allclose(lattice.evaluateRest(uvw), bernstein_ffd(bent, counts, uvw), rtol=1e-12, atol=1e-14)
    # Newton embedding finds the parameters back.
    world = bernstein_ffd(bent, counts, uvw)
    embedding = ffd.embed(lattice, world)
    assert embedding.insideCount == 50
    np.testing.assert_allclose(embedding.parameters(), uvw, atol=1e-9)


def test_cylindrical_lattice_is_periodic_in_the_angle():
    lattice = ffd.makeCylindricalLattice(counts=(3, 8, 3), innerRadius=0.0, outerRadius=1.0, zMin=0.0, zMax=2.0)
    assert lattice.basis(1).kind == ffd.AxisBasis.Kind.PeriodicBSpline
    a = lattice.evaluateRest([[0.7, 0.1, 0.5]])[0]
    b = lattice.evaluateRest([[0.7, 1.1, 0.5]])[0]
    np.testing.assert_allclose(a, b, atol=1e-14)
    angles = RNG.random(200) * 2 * np.pi
    radii = 0.2 + 0.6 * RNG.random(200)
    points = np.stack([radii * np.cos(angles), radii * np.sin(angles), 2 * RNG.random(200)], axis=1)
    embedding = ffd.embed(lattice, points)
    assert embedding.insideCount == 200
    np.testing.assert_allclose(lattice.evaluateRest(embedding.parameters()), points, atol=1e-9)


def test_lattice_errors_carry_the_cpp_messages():
    with pytest.raises(ffdkit.LatticeError, match=r"lattice needs >= 2 points per axis, got \(1, 4, 4\)"):
        ffd.makeBoxLattice(counts=(1, 4, 4))
    with pytest.raises(ValueError):  # LatticeError is a ValueError
        ffd.makeBoxLattice(counts=(3, 3, 3), bases=ffd.AxisBasis.bspline(5), capDegreeToCount=False)
    with pytest.raises(ValueError, match=r"restPoints: expected a float64 array of shape \(N, 3\), got shape \(8, 2\)"):
        ffd.makeLattice((2, 2, 2), ffd.AxisBasis.bernstein(), np.zeros((8, 2)))
    with pytest.raises(ffdkit.LatticeError, match="8 x 3"):
        bernstein_box((2, 2, 2)).setControlPoints(np.zeros((7, 3)))


# ---- embedding and deformation ------------------------------------------------------------------
def test_deform_matches_the_bernstein_formula_in_an_oriented_box():
    frame = oriented_frame()
    counts = (4, 3, 5)
    lattice = bernstein_box(counts, frame=frame)
    lattice.controlPoints[:] += 0.2 * RNG.standard_normal((lattice.pointCount, 3))
    uvw = RNG.random((2000, 3))
    points = apply_frame(frame, uvw)
    deformer = ffd.Deformer.fromPoints(lattice, points)
    out = deformer.deform(lattice, points)
    expected = apply_frame(frame, bernstein_ffd(lattice.controlPoints, counts, uvw))
    np.testing.assert_allclose(out, expected, rtol=1e-12, atol=1e-12 * np.abs(expected).max())
    assert not out.flags.writeable
    # C-ordered (copied) and Fortran-ordered (used in place) inputs give one result.
    for variant in (np.ascontiguousarray(points), np.asfortranarray(points)):
        np.testing.assert_array_equal(ffd.deformPoints(lattice, variant), out)


def test_box_bernstein_deform_matches_the_formula_for_any_input_layout():
    frame = oriented_frame()
    counts = (3, 4, 2)
    l, m, n = counts
    displacements = 0.2 * RNG.standard_normal((l * m * n, 3))
    box = ffd.BoxBernsteinLattice(counts, frame, displacements)
    np.testing.assert_array_equal(box.frame, frame)
    uvw = RNG.random((3000, 3)) * 1.4 - 0.2
    points = apply_frame(frame, uvw)
    inside = np.all((uvw >= 0) & (uvw <= 1), axis=1)
    # Rest grid (i/(l-1), j/(m-1), k/(n-1)) with flat index i + l*(j + m*k), plus the displacements.
    grid = np.stack(np.meshgrid(*[np.linspace(0, 1, c) for c in counts], indexing="ij"), axis=-1)
    control = grid.reshape((-1, 3), order="F") + displacements
    expected = apply_frame(frame, bernstein_ffd(control, counts, uvw))
    expected[~inside] = points[~inside]
    out = ffd.boxBernsteinDeform(box, points)
    assert out.shape == points.shape and out.flags.c_contiguous and out.flags.writeable
    np.testing.assert_allclose(out, expected, rtol=0, atol=1e-12 * np.abs(expected).max())
    np.testing.assert_array_equal(out[~inside], points[~inside])
    rows = np.zeros((6000, 3))
    rows[::2] = points
    for variant in (np.asfortranarray(points), rows[::2], points.T.copy().T, points.tolist()):
        np.testing.assert_array_equal(ffd.boxBernsteinDeform(box, variant), out)
    np.testing.assert_array_equal(ffd.boxBernsteinDeform(box, points[0]), out[:1])  # one point


def test_box_bernstein_deform_writes_into_out_or_in_place_and_checks_it():
    box = ffd.BoxBernsteinLattice((2, 2, 2), None, np.full((8, 3), 0.1))
    points = RNG.random((100, 3))
    expected = ffd.boxBernsteinDeform(box, points)
    np.testing.assert_allclose(expected, points + 0.1, atol=1e-15)  # a uniform shift of the unit box
    target = np.empty((100, 3), order="F")
    assert ffd.boxBernsteinDeform(box, points, out=target) is target
    np.testing.assert_array_equal(target, expected)
    moved = points.copy()
    ffd.boxBernsteinDeform(box, moved, out=moved)
    np.testing.assert_array_equal(moved, expected)
    with pytest.raises(ValueError, match=r"out: expected a float64 array of shape \(100, 3\)"):
        ffd.boxBernsteinDeform(box, points, out=np.empty((99, 3)))
    frozen = np.empty((100, 3))
    frozen.flags.writeable = False
    with pytest.raises(ValueError, match="read-only"):
        ffd.boxBernsteinDeform(box, points, out=frozen)
    shared = np.zeros((200, 3))
    with pytest.raises(ValueError, match="shares memory with points"):
        ffd.boxBernsteinDeform(box, shared[:100], out=shared[50:150])
    with pytest.raises(ffdkit.LatticeError, match=r"needs 2 to 33 points per axis, got \(1, 2, 2\)"):
        ffd.boxBernsteinDeform(ffd.BoxBernsteinLattice((1, 2, 2)), points)
    with pytest.raises(ValueError, match=r"expected a float64 array of shape \(N, 3\), got shape \(100, 2\)"):
        ffd.boxBernsteinDeform(box, points[:, :2])


def test_incremental_update_equals_a_full_deform():
    lattice = ffd.makeBoxLattice(counts=(6, 6, 6), bases=ffd.AxisBasis.bspline(3))
    points = RNG.random((5000, 3))
    deformer = ffd.Deformer(ffd.embed(lattice, points))
    deformer.deform(lattice, points)
    lattice.controlPoints[0] += [0.3, 0.0, -0.1]  # a corner point: few cells change
    updated = deformer.update(lattice, points).copy()
    stats = deformer.lastStats
    assert not stats.full and stats.changedControlPoints == 1 and 0 < stats.evaluatedPoints < 5000
    full = ffd.Deformer(ffd.embed(lattice, points))
    np.testing.assert_array_equal(updated, full.deform(lattice, points))


def test_single_precision_stays_within_its_bound_and_reaches_pipeline_stages():
    lattice = ffd.makeBoxLattice(counts=(4, 4, 4), bases=ffd.AxisBasis.bspline(3))
    points = RNG.random((20000, 3))
    moves = 0.3 * (2 * RNG.random((lattice.pointCount, 3)) - 1)
    lattice.controlPoints[:] += moves
    double = ffd.Deformer.fromPoints(lattice, points)
    assert double.precision == ffd.Precision.Double
    expected = double.deform(lattice, points).copy()
    single = ffd.Deformer.fromPoints(lattice, points)
    single.precision = ffd.Precision.Single
    out = single.deform(lattice, points)
    largest_move = np.linalg.norm(moves, axis=1).max()
    error = np.abs(out - expected).max()
    assert 0 < error < 1e-6 * largest_move
    pipeline = ffd.Pipeline(points)
    pipeline.addLattice(lattice)
    np.testing.assert_array_equal(pipeline.update(), expected)
    pipeline.precision = ffd.Precision.Single
    np.testing.assert_array_equal(pipeline.update(), out)


def test_outside_policies_and_per_point_status():
    lattice = bernstein_box((3, 3, 3), policy=ffd.OutsidePolicy.identity())
    lattice.controlPoints[:] += 0.1
    points = np.array([[0.5, 0.5, 0.5], [1.5, 0.5, 0.5], [1.0, 1.0, 1.0], [-0.25, 0.5, 0.5]])
    embedding = ffd.embed(lattice, points)
    inside, outside = int(ffd.PointStatus.Inside), int(ffd.PointStatus.Outside)
    np.testing.assert_array_equal(embedding.statuses(), [inside, outside, inside, outside])
    assert embedding.status(1) == ffd.PointStatus.Outside
    assert (embedding.insideCount, embedding.outsideCount, embedding.failedCount) == (2, 2, 0)
    out = ffd.Deformer(embedding).deform(lattice, points)
    np.testing.assert_array_equal(out[[1, 3]], points[[1, 3]])  # identity leaves them
    np.testing.assert_allclose(out[[0, 2]], points[[0, 2]] + 0.1, atol=1e-15)
    lattice.setOutsidePolicy(ffd.OutsidePolicy.extrapolate())
    extrapolated = ffd.deformPoints(lattice, points)
    np.testing.assert_allclose(extrapolated, points + 0.1, atol=1e-14)  # a translation extends everywhere
    lattice.setOutsidePolicy(ffd.OutsidePolicy.falloff(1.0))
    falloff = ffd.deformPoints(lattice, points)
    assert 0 < falloff[1, 0] - points[1, 0] < 0.1  # blended between clamp-edge and identity
    with pytest.raises(ffdkit.LatticeError):
        lattice.setOutsidePolicy(ffd.OutsidePolicy.falloff(-1.0))


def test_stale_embedding_is_refused():
    lattice = bernstein_box((2, 2, 2))
    points = RNG.random((10, 3))
    deformer = ffd.Deformer.fromPoints(lattice, points)
    lattice.frame = oriented_frame()
    with pytest.raises(ffdkit.LatticeError, match="stale"):
        deformer.deform(lattice, points)


# ---- pipelines -------------------------------------------------------------------------------------
def test_pipeline_runs_a_lattice_tree_in_pre_order():
    points = 0.2 + 0.6 * RNG.random((1000, 3))
    pipeline = ffd.Pipeline(points)
    parent = pipeline.addLattice(bernstein_box((2, 2, 2)))
    child = pipeline.addLattice(bernstein_box((3, 3, 3)), parent)
    assert pipeline.order() == [parent, child]
    assert pipeline.parent(child) == parent and pipeline.parent(parent) is None
    pipeline.lattice(parent).controlPoints[:, 0] += 0.05  # shift every point by x + 0.05
    pipeline.lattice(child).controlPoints[13, 2] += 0.2   # then bulge the centre up
    out = pipeline.update()
    assert pipeline.pointsToEmbed() == 0
    shifted = points + [0.05, 0, 0]
    child_control = pipeline.lattice(child).controlPoints
    expected = bernstein_ffd(child_control, (3, 3, 3), shifted)
    inside = np.all((shifted >= 0) & (shifted <= 1), axis=1)
    np.testing.assert_allclose(out[inside], expected[inside], atol=1e-12)
    report = pipeline.lastReport()
    assert [r.id for r in report] == [parent, child] and all(r.reembedded for r in report)
    pipeline.removeLattice(child)
    assert pipeline.order() == [parent]


# ---- direct manipulation ------------------------------------------------------------------------
def test_least_norm_control_change_moves_the_chosen_points():
    lattice = bernstein_box((4, 4, 4))
    uvw = np.array([[0.3, 0.4, 0.5], [0.8, 0.2, 0.6]])
    displacement = np.array([[0.1, 0.0, 0.05], [-0.05, 0.1, 0.0]])
    change = ffd.leastNormControlChange(lattice, uvw, displacement)
    assert change.shape == (64, 3)
    lattice.controlPoints[:] += change
    np.testing.assert_allclose(lattice.evaluate(uvw), uvw + displacement, atol=1e-13)
    # Least norm: the change lies in the row space of the basis-weight matrix B (k x N).
    weights = np.zeros((2, 64))
    for row, parameters in enumerate(uvw):
        for term in ffd.basisWeights(lattice, parameters):
            weights[row, term.point] += term.weight
    np.testing.assert_allclose(change, weights.T @ np.linalg.lstsq(weights.T, change, rcond=None)[0], atol=1e-13)


# ---- progress, cancel, and the GIL --------------------------------------------------------------
def test_progress_reports_and_cancel_raises():
    lattice = bernstein_box((3, 3, 3))
    points = RNG.random((3 * ffd.kEmbedProgressChunk + 5, 3))
    calls = []
    ffd.embed(lattice, points, ffd.EmbedOptions(parallel=False), progress=lambda d, t: calls.append((d, t)))
    n = len(points)
    assert calls[0] == (0, n) and calls[-1] == (n, n)
    assert [d for d, _ in calls] == sorted(d for d, _ in calls) and len(calls) >= 4
    with pytest.raises(ffdkit.Cancelled):
        ffd.embed(lattice, points, progress=lambda d, t: d == 0)
    with pytest.raises(ZeroDivisionError):
        ffd.embed(lattice, points, progress=lambda d, t: 1 / 0)


def test_embedding_releases_the_gil():
    counts = (4, 4, 4)
    rest = ffd.makeBoxLattice(counts=counts, bases=ffd.AxisBasis.bernstein()).restPoints
    lattice = ffd.makeLattice(counts, ffd.AxisBasis.bernstein(), rest + 0.03 * np.sin(5 * rest))  # Newton
    points = 0.1 + 0.8 * RNG.random((200000, 3))
    ticks = [0]
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks[0] += 1

    thread = threading.Thread(target=count)
    thread.start()
    try:
        time.sleep(0.01)
        before = ticks[0]
        started = time.perf_counter()
        ffd.embed(lattice, points)
        seconds = time.perf_counter() - started
        during = ticks[0] - before
    finally:
        stop.set()
        thread.join()
    # With the GIL held for the whole call the counting thread could not run at all.
    assert seconds > 0.02, "the embedding was too quick to tell"
    assert during > 1000
