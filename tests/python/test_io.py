"""ffdkit.io: volume meshes read to numpy points and written back by pass-through, and the
handler classes with PyGeM's names, against PyGeM's own test data (tests/data/pygem)."""
import os
import struct

import numpy as np
import pytest

import ffdkit
from ffdkit import io

DATA = os.path.join(os.path.dirname(__file__), "..", "data", "pygem")


def data(name):
    return os.path.join(DATA, name)


# PyGeM's tests (tests/test_*handler.py): values at points, and the changes their write tests make.
CASES = [
    (io.UnvHandler, "test_square.unv", "test_square_out_true.unv",
     [(33, 0, 1.0), (178, 1, 0.4), (100, 2, 0.0), (0, 0, 0.0), (-1, 2, 0.0)],
     [(0, 0, 2.2), (5, 1, 4.3), (9, 2, 0.5), (45, 0, 7.2), (132, 1, -1.2), (255, 2, -3.6)]),
    (io.KHandler, "test_square.k", "test_square_out_true.k",
     [(33, 0, 1.0), (178, 1, 0.4), (100, 2, 0.0), (0, 0, 0.0), (-1, 2, 0.0)],
     [(0, 0, 2.2), (5, 1, 4.3), (9, 2, 0.5), (45, 0, 7.2), (132, 1, -1.2), (255, 2, -3.6)]),
    (io.ElmerHandler, "test_elmer.nodes", "test_elmer_out_true.nodes",
     [(33, 0, 2.94650796191), (149, 1, 2.0), (239, 2, 0.0), (0, 0, 0.0), (-1, 1, 2.0)],
     [(row, j, v) for row, xyz in [(0, [0.1, 1.1, 0.1]), (1, [0.1, 1.2, 0.1]), (2, [0.1, 1.6, 0.1]),
                                   (149, [11.7910193185, 2.0, 0.1]), (150, [12.858303628, 0.0, 0.1]),
                                   (151, [12.858303628, 0.125, 0.1]), (-3, [26.2, 1.6, 0.1]),
                                   (-2, [26.2, 2.01666666667, 0.1]), (-1, [26.2, 2.1, 0.1])]
      for j, v in enumerate(xyz)]),
    (io.MdpaHandler, "test_square.mdpa", "test_square_out_true.mdpa",
     [(190, 0, 1.0), (72, 1, 0.4), (100, 2, 0.0), (0, 0, 0.0), (-1, 2, 0.0)],
     [(0, 0, 0.0), (5, 1, 1.0), (9, 2, 0.0), (44, 0, 0.0), (122, 1, 0.2), (255, 2, 0.0)]),
]


@pytest.mark.parametrize("handler,name,expected,values,changes", CASES)
def test_handlers_parse_what_pygems_tests_expect(handler, name, expected, values, changes):
    points = handler().parse(data(name))
    assert points.dtype == np.float64 and points.shape[1] == 3
    for i, j, value in values:
        np.testing.assert_almost_equal(points[i][j], value)


@pytest.mark.parametrize("handler,name,expected,values,changes", CASES)
def test_handlers_write_the_points_pygems_writer_writes(handler, name, expected, values, changes, tmp_path):
    h = handler()
    points = h.parse(data(name))
    out = str(tmp_path / ("out" + os.path.splitext(name)[1]))
    h.write(points, out)
    assert h.outfile == out
    assert open(out, "rb").read() == open(data(name), "rb").read()  # unchanged points: the same bytes
    for i, j, value in changes:
        points[i][j] = value
    h.write(points, out)
    np.testing.assert_array_equal(handler().parse(out), points)
    np.testing.assert_allclose(handler().parse(data(expected)), points, rtol=0, atol=1e-9)


def test_handlers_check_their_arguments_as_pygems_do(tmp_path):
    h = io.UnvHandler()
    with pytest.raises(TypeError):
        h.parse(5.2)
    with pytest.raises(ValueError):
        h.parse(data("test_square.k"))
    with pytest.raises(RuntimeError):
        h.write(np.zeros((20, 3)), str(tmp_path / "a.unv"))
    h.parse(data("test_square.unv"))
    with pytest.raises(ffdkit.MeshIoError, match="20 points given for a file of 256"):
        h.write(np.zeros((20, 3)), str(tmp_path / "a.unv"))


def two_tets_binary():
    """A Gmsh MSH 4.1 binary file of two tetrahedra, written value by value."""
    b = b"$MeshFormat\n4.1 1 8\n" + struct.pack("<i", 1) + b"\n$EndMeshFormat\n$Nodes\n"
    b += struct.pack("<4Q", 1, 5, 1, 5) + struct.pack("<iiiQ", 3, 1, 0, 5) + struct.pack("<5Q", 1, 2, 3, 4, 5)
    b += struct.pack("<15d", 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1)
    b += b"\n$EndNodes\n$Elements\n" + struct.pack("<4Q", 1, 2, 1, 2) + struct.pack("<iiiQ", 3, 1, 4, 2)
    b += struct.pack("<10Q", 1, 1, 2, 3, 4, 2, 2, 5, 3, 4) + b"\n$EndElements\n"
    return b


def test_read_and_write_mesh_keep_every_other_byte(tmp_path):
    path = tmp_path / "two.msh"
    path.write_bytes(two_tets_binary())
    points = io.read_mesh(path)
    np.testing.assert_array_equal(points[4], [1, 1, 1])
    moved = points * 2.0 + 0.25
    io.write_mesh(tmp_path / "moved.msh", moved, like=path, check=True)
    np.testing.assert_array_equal(io.read_mesh(tmp_path / "moved.msh"), moved)
    written = (tmp_path / "moved.msh").read_bytes()
    original = two_tets_binary()
    assert written[written.index(b"$Elements"):] == original[original.index(b"$Elements"):]
    assert len(written) == len(original)


def test_write_mesh_refuses_inverted_cells(tmp_path):
    path = tmp_path / "two.msh"
    path.write_bytes(two_tets_binary())
    points = io.read_mesh(path)
    points[:, 2] *= -1.0  # a reflection inverts both tetrahedra
    mesh = io.read_volume_mesh(str(path))
    quality = mesh.check(points)
    assert quality["checked"] and quality["bad_cells"] == 2 and not quality["ok"]
    with pytest.raises(ValueError, match="2 cells inverted"):
        io.write_mesh(tmp_path / "out.msh", points, like=path, check=True)
    assert not (tmp_path / "out.msh").exists()


def test_formats_and_errors():
    assert io.volume_mesh_format("a.su2") == io.VolumeMeshFormat.Su2
    assert io.volume_mesh_format("a.ply") is None
    with pytest.raises(ffdkit.MeshIoError, match="not a volume mesh"):
        io.read_mesh("a.ply")
    with pytest.raises(ffdkit.MeshIoError, match="test_elmer.nodes"):
        io.read_mesh(data("test_square.unv").replace("test_square.unv", "missing/test_elmer.nodes"))
