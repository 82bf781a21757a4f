"""ffdkit.cad from Python: STEP and IGES round trips, the exact FFD of a part against independent
expectations (an affine lattice scales the volume exactly; a bent lattice's solid encloses the
volume of the FFD of its tessellation), the pole method for comparison, and errors naming the file."""

import math

import numpy as np
import pytest

import ffdkit
from ffdkit import ffd

import ffdkit.cad as cad  # tests/python/CMakeLists.txt runs this file only in builds with OpenCASCADE

# The filleted box: 60 x 40 x 30, every edge rounded with radius 5 (a 50 x 30 x 20 box swept by a
# ball of radius 5: Steiner's formula).
A, B, C, R = 50.0, 30.0, 20.0, 5.0
FILLETED_BOX_VOLUME = A * B * C + 2 * R * (A * B + B * C + A * C) + math.pi * R * R * (A + B + C) + 4 / 3 * math.pi * R ** 3


def lattice_around(model, counts=(3, 3, 3), margin=1.0):
    low, high = model.bounds
    return ffd.makeBoxLattice(counts=counts, bases=ffd.AxisBasis.bernstein(), boxMin=np.asarray(low) - margin,
                              boxMax=np.asarray(high) + margin)


@pytest.fixture(scope="module")
def box():
    return cad.make_sample_part("filleted-box")


def test_the_sample_part_is_a_valid_solid_of_the_right_volume(box):
    assert box.part_count == 1
    assert box.counts["solids"] == 1
    checked = cad.check(box)
    assert checked["valid"], checked["first_problem"]
    assert checked["volume"] == pytest.approx(FILLETED_BOX_VOLUME, rel=1e-9)


def test_step_and_iges_round_trips_keep_the_solid(box, tmp_path):
    cad.write_step(box, tmp_path / "box.step")
    cad.write_iges(box, str(tmp_path / "box.igs"))
    for model in (cad.read_step(tmp_path / "box.step"), cad.read_iges(tmp_path / "box.igs")):
        assert model.counts["faces"] == box.counts["faces"]
        np.testing.assert_allclose(model.bounds[0], box.bounds[0], atol=1e-6)
        np.testing.assert_allclose(model.bounds[1], box.bounds[1], atol=1e-6)
    assert cad.check(cad.read_step(tmp_path / "box.step"))["volume"] == pytest.approx(FILLETED_BOX_VOLUME, rel=1e-9)


def test_the_tessellation_encloses_the_part(box):
    points, triangles, parts = cad.tessellate(box, linear_deflection=0.01)
    assert points.shape[1] == 3 and triangles.shape[1] == 3 and parts.shape == (triangles.shape[0],)
    assert np.all(parts == 0)
    assert cad.enclosed_volume(points, triangles) == pytest.approx(FILLETED_BOX_VOLUME, rel=1e-3)
    # Split down to edges of 2 mm: the same surface (every midpoint on a straight edge of it, every
    # split edge split in both its triangles: still closed), no edge longer.
    fine, fine_triangles, fine_parts = cad.tessellate(box, linear_deflection=0.01, max_edge_length=2.0)
    corners = fine[fine_triangles]
    edges = np.linalg.norm(corners - np.roll(corners, 1, axis=1), axis=2)
    assert edges.max() <= 2.0 and len(fine_triangles) > 10 * len(triangles)
    assert cad.enclosed_volume(fine, fine_triangles) == pytest.approx(cad.enclosed_volume(points, triangles), rel=1e-12)
    assert fine_parts.shape == (len(fine_triangles),)


def test_an_affine_lattice_scales_the_volume_exactly(box):
    lattice = lattice_around(box)
    x0 = lattice.restPoints[:, 0].min()
    lattice.controlPoints[:, 0] = x0 + 2.0 * (lattice.controlPoints[:, 0] - x0)
    deformed, report = cad.deform(box, lattice)
    assert report["faces"] == box.counts["faces"]
    checked = cad.check(deformed)
    assert checked["valid"], checked["first_problem"]
    assert checked["volume"] == pytest.approx(2.0 * FILLETED_BOX_VOLUME, rel=1e-9)


def test_the_exact_method_is_the_ffd_of_the_surface_and_the_pole_method_is_not(box, tmp_path):
    lattice = lattice_around(box)
    size = np.linalg.norm(np.subtract(*box.bounds))
    lattice.controlPoints[22] += [0.0, 0.0, 0.2 * size]  # the top centre point up: a bulge
    lattice.controlPoints[13] += [0.2 * size, 0.0, 0.0]  # the centre point sideways: a bend
    exact, exact_report = cad.deform(box, lattice, method="exact", samples=9)
    poles, poles_report = cad.deform(box, lattice, method="poles", samples=9)
    assert exact_report["max_deviation"] < 1e-9 * size
    assert poles_report["max_deviation"] > 1e-4 * size
    assert exact_report["max_gap"] < 1e-6 * size
    # Independently: the FFD of the original's fine tessellation encloses the written solid's volume.
    points, triangles, _ = cad.tessellate(box, linear_deflection=1e-4 * size, max_edge_length=0.01 * size)
    moved = ffd.deformPoints(lattice, points)
    cad.write_step(exact, tmp_path / "exact.step")
    written = cad.check(cad.read_step(tmp_path / "exact.step"))
    assert written["valid"], written["first_problem"]
    assert written["volume"] == pytest.approx(cad.enclosed_volume(moved, triangles), rel=2e-4)
    assert abs(written["volume"] - FILLETED_BOX_VOLUME) > 0.01 * FILLETED_BOX_VOLUME


def test_errors_name_the_file_and_the_argument(box, tmp_path):
    bad = tmp_path / "not-a-part.step"
    bad.write_text("this is not STEP\n")
    with pytest.raises(cad.CadError, match="not-a-part.step") as raised:
        cad.read_step(bad)
    assert isinstance(raised.value, ffdkit.Error) and isinstance(raised.value, RuntimeError)
    with pytest.raises(cad.CadError, match="missing.igs"):
        cad.read_iges(tmp_path / "missing.igs")
    with pytest.raises(ValueError, match="'exact' or 'poles'"):
        cad.deform(box, lattice_around(box), method="approximate")
    with pytest.raises(ValueError, match="unknown sample part 'teapot'"):
        cad.make_sample_part("teapot")
    with pytest.raises(cad.CadError, match="maxDegree must be in"):
        cad.deform(box, lattice_around(box), max_degree=0)


def test_every_function_says_its_arguments_result_and_errors():
    for name in cad.__all__:
        obj = getattr(cad, name)
        if name in ("CadError", "Model"):
            assert len((obj.__doc__ or "").strip().splitlines()) >= 2, name
            continue
        for section in ("Args:", "Returns:", "Raises:"):
            assert section in obj.__doc__, f"ffdkit.cad.{name} lacks {section}"
