"""ffdkit.pygem.FFD against PyGeM's documented behaviour: PyGeM's own FFD test cases (rewritten;
their .prm input recreated from the documented values) and an independent numpy Bernstein
evaluator (1e-12 relative) on rotated boxes, points outside and exactly on faces."""

import copy
import os

import numpy as np
import pytest

from ffdkit.pygem import FFD
from reference import bernstein, rotation

RNG = np.random.default_rng(7)

# PyGeM's tests/test_datasets/parameters_sphere.prm, recreated from its documented values.
SPHERE_PRM = """
[Box info]
n control points x: 3
n control points y: 2
n control points z: 2
box length x: 45.0
box length y: 90.0
box length z: 90.0
box origin x: -20.0
box origin y: -55.0
box origin z: -45.0
rotation angle x: 20.3
rotation angle y: 11
rotation angle z: 0

[Parameters weights]
parameter x: 0   0   0    .2
             1   0   0   0.5
             2   0   0   1.0
parameter y: 0   1   0   0.5555555555
             2   0   0  -1.0
parameter z: 0   0   1   -.2
             0   1   1  -0.456229852
             2   0   0  -1.22
             2   1   0  -1.0
"""

HEAD = """
[Box info]
# This section collects all the properties of the FFD bounding box.

# n control points indicates the number of control points in each direction (x, y, z).
# For example, to create a 2 x 3 x 2 grid, use the following: n control points: 2, 3, 2
n control points x: {n[0]}
n control points y: {n[1]}
n control points z: {n[2]}

# box length indicates the length of the FFD bounding box along the three canonical directions (x, y, z).
# It uses the local coordinate system.
# For example to create a 2 x 1.5 x 3 meters box use the following: box length: 2.0, 1.5, 3.0
box length x: {L[0]}
box length y: {L[1]}
box length z: {L[2]}

# box origin indicates the x, y, and z coordinates of the origin of the FFD bounding box. That is center of
# rotation of the bounding box. It corresponds to the point coordinates with position [0][0][0].
# See section "Parameters weights" for more details.
# For example, if the origin is equal to 0., 0., 0., use the following: box origin: 0., 0., 0.
box origin x: {o[0]}
box origin y: {o[1]}
box origin z: {o[2]}

# rotation angle indicates the rotation angle around the x, y, and z axis of the FFD bounding box in degrees.
# The rotation is done with respect to the box origin.
# For example, to rotate the box by 2 deg along the z direction, use the following: rotation angle: 0., 0., 2.
rotation angle x: {a[0]}
rotation angle y: {a[1]}
rotation angle z: {a[2]}


[Parameters weights]
# This section describes the weights of the FFD control points.
# We adopt the following convention:
# For example with a 2x2x2 grid of control points we have to fill a 2x2x2 matrix of weights.
# If a weight is equal to zero you can discard the line since the default is zero.
#
# | x index | y index | z index | weight |
#  --------------------------------------
# |    0    |    0    |    0    |  1.0   |
# |    0    |    1    |    1    |  0.0   | --> you can erase this line without effects
# |    0    |    1    |    0    | -2.1   |
# |    0    |    0    |    1    |  3.4   |
"""


def expected_prm(n, length, origin, angles, weights):
    """The bytes PyGeM writes: HEAD, then per axis a comment and `i   j   k   value` rows."""
    text = HEAD.format(n=n, L=length, o=origin, a=angles)
    for letter, rows in zip("xyz", weights):
        text += "\n# parameter {0} collects the displacements along {0}, normalized with the box length {0}.".format(letter)
        text += "\nparameter {}:".format(letter)
        for r, (i, j, k, value) in enumerate(rows):
            text += (" " if r == 0 else " " * 13) + "{}   {}   {}   {}\n".format(i, j, k, value)
    return text


def zero_rows(n):
    return [(i, j, k, "0.0") for i in range(n[0]) for j in range(n[1]) for k in range(n[2])]


@pytest.fixture
def sphere_prm(tmp_path):
    path = tmp_path / "parameters_sphere.prm"
    path.write_text(SPHERE_PRM)
    return str(path)


def pygem_reference(params, points):
    """PyGeM's FFD written independently: box coordinates u = diag(1/L) R^T (x - origin) with
    R = Rx Ry Rz; points with u in [0, 1]^3 (to 1e-12) move to origin + R diag(L) (u + sum B mu)."""
    r = rotation(0, params.rot_angle[0]) @ rotation(1, params.rot_angle[1]) @ rotation(2, params.rot_angle[2])
    length = np.asarray(params.box_length, dtype=float)
    u = ((points - params.box_origin) @ r) / length
    inside = np.all((u >= -1e-12) & (u <= 1 + 1e-12), axis=1)
    l, m, n = params.array_mu_x.shape
    mu = np.stack([params.array_mu_x, params.array_mu_y, params.array_mu_z], axis=-1)
    shift = np.einsum("pi,pj,pk,ijkc->pc", bernstein(l - 1, u[:, 0]), bernstein(m - 1, u[:, 1]),
                      bernstein(n - 1, u[:, 2]), mu)
    out = points.copy()
    out[inside] = params.box_origin + ((u[inside] + shift[inside]) * length) @ r.T
    return out, inside


def assert_close_relative(actual, expected, rtol=1e-12):
    scale = max(1.0, np.abs(expected).max())
    np.testing.assert_allclose(actual, expected, rtol=0, atol=rtol * scale)


# ---- PyGeM's test cases, rewritten --------------------------------------------------------------
def test_defaults():
    params = FFD()
    assert np.array_equal(params.n_control_points, [2, 2, 2])
    assert params.conversion_unit == 1.
    assert np.array_equal(params.box_length, np.ones(3))
    assert np.array_equal(params.box_origin, np.zeros(3))
    assert np.array_equal(params.rot_angle, np.zeros(3))
    for mu in (params.array_mu_x, params.array_mu_y, params.array_mu_z):
        np.testing.assert_array_equal(mu, np.zeros((2, 2, 2)))
    np.testing.assert_array_almost_equal(params.rotation_matrix, np.eye(3))
    np.testing.assert_array_almost_equal(params.position_vertices, [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])


def test_generic_counts_and_setting_counts_resets_the_weights():
    params = FFD([2, 3, 5])
    assert np.array_equal(params.n_control_points, [2, 3, 5])
    assert params.array_mu_x.shape == params.array_mu_y.shape == params.array_mu_z.shape == (2, 3, 5)
    params.array_mu_x[1, 2, 3] = 0.5
    params.n_control_points = [3, 3, 3]
    np.testing.assert_array_equal(params.array_mu_x, np.zeros((3, 3, 3)))


@pytest.mark.parametrize("axis, counts", [(0, [3, 3, 5]), (1, [2, 5, 5]), (2, [2, 3, 9])])
def test_reflect_doubles_counts_and_length(axis, counts):
    params = FFD([2, 3, 5])
    params.reflect(axis=axis)
    assert np.array_equal(params.n_control_points, counts)
    assert params.box_length[axis] == 2


def test_reflect_rejects_a_bad_axis_and_a_deformed_symmetry_plane(sphere_prm):
    with pytest.raises(ValueError):
        FFD([2, 3, 5]).reflect(axis=4)
    for axis, name in enumerate(["array_mu_x", "array_mu_y", "array_mu_z"]):
        params = FFD([3, 2, 2])
        params.read_parameters(sphere_prm)
        setattr(params, name, np.array([0.2, 0., 0., 0., 0.5, 0., 0., 0., 1., 0., 0.3, 0.1]).reshape((3, 2, 2)))
        with pytest.raises(RuntimeError):
            params.reflect(axis=axis)


def test_reflect_weights(sphere_prm):
    cases = [
        (0, "array_mu_x", [0.2, 0., 0., 0., 0.5, 0., 0., .2, 0., 0., 0., 0.],
         [0.2, 0., 0., 0., 0.5, 0., 0., 0.2, 0., 0., 0., 0., -0.5, -0., -0., -0.2, -0.2, -0., -0., -0.], (5, 2, 2)),
        (1, "array_mu_y", [0.2, 0., 0., 0., 0.5, 0., 0., 0., 0., 0., 0., 0.],
         [0.2, 0., 0., 0., -0.2, -0., 0.5, 0., 0., 0., -0.5, -0., 0., 0., 0., 0., 0., 0.], (3, 3, 2)),
        (2, "array_mu_z", [0.2, 0., 0., 0., 0.5, 0., 0., 0., 0., 0., 0., 0.],
         [0.2, 0., -0.2, 0., 0., 0., 0.5, 0., -0.5, 0., 0., -0., 0., 0., -0., 0., 0., -0.], (3, 2, 3)),
    ]
    for axis, name, before, after, shape in cases:
        params = FFD([3, 2, 2])
        params.read_parameters(sphere_prm)
        setattr(params, name, np.array(before).reshape((3, 2, 2)))
        original = copy.deepcopy(params)
        copied = params.reflect(axis=axis, in_place=False)
        np.testing.assert_array_equal(getattr(params, name), getattr(original, name))  # untouched
        assert params.reflect(axis=axis) is None
        for result in (params, copied):
            np.testing.assert_array_almost_equal(getattr(result, name), np.array(after).reshape(shape))


def test_read_parameters(sphere_prm):
    params = FFD(n_control_points=[3, 2, 2])
    params.read_parameters(sphere_prm)
    assert params.conversion_unit == 1.
    assert np.array_equal(params.n_control_points, [3, 2, 2])
    assert np.array_equal(params.box_length, [45.0, 90.0, 90.0])
    np.testing.assert_array_almost_equal(params.box_origin, [-20.0, -55.0, -45.0])
    assert np.array_equal(params.rot_angle, [20.3, 11.0, 0.])
    np.testing.assert_array_almost_equal(
        params.array_mu_x, np.array([0.2, 0., 0., 0., 0.5, 0., 0., 0., 1., 0., 0., 0.]).reshape((3, 2, 2)))
    np.testing.assert_array_almost_equal(
        params.array_mu_y, np.array([0., 0., 0.5555555555, 0., 0., 0., 0., 0., -1., 0., 0., 0.]).reshape((3, 2, 2)))
    np.testing.assert_array_almost_equal(
        params.array_mu_z,
        np.array([0., -0.2, 0., -0.45622985, 0., 0., 0., 0., -1.22, 0., -1., 0.]).reshape((3, 2, 2)))
    np.testing.assert_array_almost_equal(
        params.rotation_matrix,
        [[0.98162718, 0., 0.190809], [0.06619844, 0.93788893, -0.34056147], [-0.17895765, 0.34693565, 0.92065727]])
    np.testing.assert_array_almost_equal(params.position_vertices[0], params.box_origin)
    np.testing.assert_array_almost_equal(
        params.position_vertices,
        [[-20.0, -55.0, -45.0], [24.17322326, -52.02107006, -53.05309404], [-20., 29.41000412, -13.77579136],
         [-2.82719042, -85.65053198, 37.85915459]])


def test_filename_must_be_a_string():
    with pytest.raises(TypeError):
        FFD([3, 2, 2]).read_parameters(3)
    with pytest.raises(TypeError):
        FFD([3, 2, 2]).write_parameters(5)


def test_default_parameter_file_is_byte_compatible(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    expected = expected_prm([3, 2, 2], ["1.0"] * 3, ["0.0"] * 3, ["0.0"] * 3, [zero_rows((3, 2, 2))] * 3)
    FFD(n_control_points=[3, 2, 2]).write_parameters()
    assert open("parameters.prm").read() == expected
    os.remove("parameters.prm")
    FFD(n_control_points=[3, 2, 2]).read_parameters()  # a missing file is written with the defaults
    assert open("parameters.prm").read() == expected


def test_written_parameters_are_byte_compatible_and_round_trip(sphere_prm, tmp_path):
    params = FFD([3, 2, 2])
    params.read_parameters(sphere_prm)
    out = str(tmp_path / "out.prm")
    params.write_parameters(out)
    values = {(0, 0, 0): ".2", (1, 0, 0): "0.5", (2, 0, 0): "1.0"}, \
        {(0, 1, 0): "0.5555555555", (2, 0, 0): "-1.0"}, \
        {(0, 0, 1): "-0.2", (0, 1, 1): "-0.456229852", (2, 0, 0): "-1.22", (2, 1, 0): "-1.0"}
    weights = [[(i, j, k, str(float(v.get((i, j, k), "0.0")))) for (i, j, k, _) in zero_rows((3, 2, 2))] for v in values]
    expected = expected_prm([3, 2, 2], ["45.0", "90.0", "90.0"], ["-20.0", "-55.0", "-45.0"],
                            ["20.3", "11.0", "0.0"], weights)
    assert open(out).read() == expected
    again = FFD([2, 2, 2])
    again.read_parameters(out)
    for name in ("n_control_points", "box_length", "box_origin", "rot_angle", "array_mu_x", "array_mu_y", "array_mu_z"):
        np.testing.assert_array_equal(getattr(again, name), getattr(params, name))


def test_print_and_position_of_vertices_and_reset():
    text = str(FFD(n_control_points=[3, 2, 2]))
    assert text.startswith("conversion_unit = 1.0\nn_control_points = [3 2 2]\n\nbox_length = [1. 1. 1.]\n")
    assert "\nrotation_matrix = \n" in text and text.endswith("\n")
    params = FFD()
    params.box_origin = np.array([0., 0., 0.])
    params.box_length = np.array([1., 1., 1.])
    np.testing.assert_almost_equal(params.position_vertices, [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]])
    params = FFD([5, 5, 5])
    params.array_mu_y[:] = 1.0
    params.reset_weights()
    for mu in (params.array_mu_x, params.array_mu_y, params.array_mu_z):
        np.testing.assert_array_equal(mu, np.zeros((5, 5, 5)))


# ---- the deformation against the independent evaluator ------------------------------------------
def test_rotated_box_inside_and_outside_points(sphere_prm):
    params = FFD()
    params.read_parameters(sphere_prm)
    points = np.array([-60.0, -110.0, -90.0]) + RNG.random((20000, 3)) * np.array([130.0, 180.0, 180.0])
    expected, inside = pygem_reference(params, points)
    assert 1000 < inside.sum() < 19000  # both kinds present
    result = params(points)
    assert result.shape == points.shape and result.flags.writeable
    assert_close_relative(result, expected)
    np.testing.assert_array_equal(result[~inside], points[~inside])  # outside: unchanged, bit for bit


@pytest.mark.parametrize("angles", [(0., 0., 0.), (30., 0., 0.), (0., -45., 0.), (10., 20., 30.), (-170., 95., 5.)])
def test_random_weights_in_rotated_boxes(angles):
    params = FFD([4, 3, 5])
    params.box_origin = np.array([0.5, -1.0, 2.0])
    params.box_length = np.array([2.0, 0.75, 1.25])
    params.rot_angle = np.array(angles)
    for mu in (params.array_mu_x, params.array_mu_y, params.array_mu_z):
        mu[:] = 0.3 * RNG.standard_normal(mu.shape)
    u = RNG.random((5000, 3)) * 1.4 - 0.2
    points = params.box_origin + (u * params.box_length) @ params.rotation_matrix.T
    expected, inside = pygem_reference(params, points)
    assert_close_relative(params(points), expected)
    # psi / inverse_psi / T compose to the same map inside the box.
    reference = params.psi(points[inside] - params.box_origin)
    np.testing.assert_allclose(reference, u[inside], atol=1e-12)
    composed = params.inverse_psi(params.T(reference)) + params.box_origin
    assert_close_relative(composed, expected[inside])


def test_points_exactly_on_faces_are_deformed():
    params = FFD([3, 3, 3])
    params.box_length = np.array([1.0, 2.0, 4.0])  # exact box coordinates
    params.array_mu_x[2, 1, 1] = 0.25  # on the face x = 1
    params.array_mu_z[1, 1, 0] = -0.5  # on the face z = 0
    faces = np.array([[1.0, 1.0, 2.0], [0.5, 1.0, 0.0], [1.0, 2.0, 4.0], [0.0, 0.0, 0.0], [0.5, 2.0, 1.0]])
    expected, inside = pygem_reference(params, faces)
    assert inside.all()
    result = params(faces)
    assert_close_relative(result, expected)
    assert result[0, 0] == pytest.approx(1.0 + 0.25 * 0.5 ** 2)  # B_2(1) = 1 on x, B_1(1/2) = 1/2 on y and z
    just_outside = faces * np.array([1.0 + 1e-9, 1.0, 1.0]) + np.array([1e-9, 0, 0])
    moved_out = params(just_outside[:1])
    np.testing.assert_array_equal(moved_out, just_outside[:1])


def test_control_points_of_the_lattice():
    params = FFD([3, 2, 4])
    params.box_origin = np.array([1.0, 2.0, 3.0])
    params.box_length = np.array([2.0, 1.0, 3.0])
    params.rot_angle = np.array([0.0, 0.0, 90.0])
    params.array_mu_y[1, 0, 2] = 0.5
    rest = params.control_points(deformed=False)
    assert rest.shape == (24, 3)
    # Row (i, j, k) with k fastest: origin + R (i L_x/2, j L_y, k L_z/3); R turns x into y.
    i, j, k = 1, 0, 2
    row = (i * 2 + j) * 4 + k
    np.testing.assert_allclose(rest[row], [1.0 - 0.0, 2.0 + 1.0, 3.0 + 2.0], atol=1e-14)
    moved = params.control_points()
    np.testing.assert_allclose(moved[row] - rest[row], [-0.5, 0.0, 0.0], atol=1e-14)  # +0.5 L_y along y turns to -x
    np.testing.assert_allclose(np.delete(moved, row, axis=0), np.delete(rest, row, axis=0), atol=1e-14)


def test_input_is_not_modified_and_bad_weights_are_reported():
    params = FFD([2, 2, 2])
    params.array_mu_x[1, 1, 1] = 0.3
    points = RNG.random((100, 3))
    kept = points.copy()
    params(points)
    np.testing.assert_array_equal(points, kept)
    params.array_mu_y = np.zeros((3, 2, 2))
    with pytest.raises(ValueError, match=r"array_mu_y has shape \(3, 2, 2\), expected n_control_points \(2, 2, 2\)"):
        params(points)
