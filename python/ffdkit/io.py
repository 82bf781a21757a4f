"""Volume meshes of CFD and FEM solvers, read to numpy points and written back by pass-through.

``read_mesh(path)`` gives the points of an OpenFOAM case (or polyMesh folder), a Gmsh ``.msh``
(4.1, ASCII or binary), SU2 ``.su2``, UNV ``.unv``, Elmer ``mesh.nodes``, LS-DYNA ``.k`` or
Kratos ``.mdpa`` file as a float64 array of shape (N, 3); ``write_mesh(path, points, like=...)``
writes the file ``like`` with those points: every byte but the coordinates as it was read
(docs/volume-meshes.md). ``read_volume_mesh`` keeps the file for several writes and checks
cells (inverted or zero-volume cells) before writing.

The handler classes have the names and methods of PyGeM's file handlers (``pygem.UnvHandler``
etc.: ``parse(filename)`` returns the points, ``write(mesh_points, filename)`` writes the parsed
file with new points), so a PyGeM script swaps its import::

    from ffdkit.io import UnvHandler     # was: from pygem import UnvHandler
"""

import os as _os

from ._ffdkit import _io

VolumeMesh = _io.VolumeMesh
VolumeMeshFormat = _io.VolumeMeshFormat
read_volume_mesh = _io.read_volume_mesh
volume_mesh_format = _io.volume_mesh_format


def read_mesh(path, max_memory=None, max_points=None):
    """The points of the volume mesh at ``path``: a float64 array of shape (N, 3).

    ``path`` is an OpenFOAM case or polyMesh folder, or a .msh, .su2, .unv, .nodes, .k, .key or
    .mdpa file (its format from the extension). A 2D SU2 mesh's z is 0. Raises
    ``ffdkit.MeshIoError`` naming the file and the line or byte offset of what is wrong.
    """
    return read_volume_mesh(str(path), max_memory, max_points).points.copy()


def write_mesh(path, points, like, check=False, durable=True):
    """Writes the volume mesh ``like`` with ``points`` (N, 3) as its coordinates to ``path``.

    Every byte of ``like`` but the coordinates is written as it was read (for an OpenFOAM case,
    every file of the folder but ``points``); ``path`` is written all or nothing. With ``check``
    the cells are checked first and a mesh with inverted or zero-volume cells raises ValueError
    (nothing written). Raises ``ffdkit.MeshIoError`` for a point count that differs from
    ``like``'s.
    """
    mesh = read_volume_mesh(str(like))
    if check:
        quality = mesh.check(points)
        if not quality["ok"]:
            raise ValueError("%s: %s; nothing written" % (path, quality["bad_text"]))
    mesh.write(points, str(path), durable)


class _Handler:
    """PyGeM's FileHandler: ``infile``, ``outfile``, ``extensions``, parse and write."""

    extensions = []

    def __init__(self):
        """A handler that has parsed nothing yet (infile and outfile are None)."""
        self.infile = None
        self.outfile = None
        self._mesh = None

    def _check(self, filename):
        if not isinstance(filename, str):
            raise TypeError("The given filename ({0!s}) must be a string".format(filename))
        extension = _os.path.splitext(filename)[1]
        if extension not in self.extensions:
            raise ValueError("The input file does not have the proper extension. It is {0!s}, instead of {1!s}.".format(
                extension, self.extensions))

    def parse(self, filename):
        """Reads ``filename`` and returns its points, a float64 array of shape (N, 3).

        The file is kept for write(). Raises TypeError for a filename that is not a string,
        ValueError for another extension, ``ffdkit.MeshIoError`` for a malformed file.
        """
        self._check(filename)
        self._mesh = read_volume_mesh(filename)
        self.infile = filename
        return self._mesh.points.copy()

    def write(self, mesh_points, filename):
        """Writes the parsed file with ``mesh_points`` (N, 3) as its coordinates to ``filename``.

        Every other byte is the parsed file's. Raises RuntimeError when nothing was parsed,
        TypeError / ValueError for a bad filename, ``ffdkit.MeshIoError`` for a point count
        that differs.
        """
        self._check(filename)
        if self._mesh is None:
            raise RuntimeError("You can not write a file without having parsed one.")
        self.outfile = filename
        self._mesh.write(mesh_points, filename)


class UnvHandler(_Handler):
    """Universal files (.unv): the nodes of dataset 2411, as PyGeM's UnvHandler.

    parse(filename) returns the nodes' coordinates; write(mesh_points, filename) writes them in
    their 25-character fields, every other line as read.
    """

    extensions = [".unv"]


class ElmerHandler(_Handler):
    """Elmer's mesh.nodes files ("node partition x y z" per line), as PyGeM's ElmerHandler.

    parse(filename) returns the coordinates; write(mesh_points, filename) replaces them, the
    node and partition numbers kept.
    """

    extensions = [".nodes"]


class KHandler(_Handler):
    """LS-DYNA keyword files (.k): the *NODE cards, as PyGeM's KHandler.

    Fixed columns (I8, 3 E16.0) or comma-separated; write keeps each value in its column.
    """

    extensions = [".k"]


class MdpaHandler(_Handler):
    """Kratos model part files (.mdpa): the "Begin Nodes" blocks, as PyGeM's MdpaHandler.

    parse(filename) returns the nodes' coordinates; write(mesh_points, filename) replaces them.
    """

    extensions = [".mdpa"]


class GmshHandler(_Handler):
    """Gmsh MSH 4.1 files (.msh), ASCII or binary; not one of PyGeM's handlers.

    parse and write as the PyGeM-style handlers; elements, entities and physical groups kept.
    """

    extensions = [".msh"]


class Su2Handler(_Handler):
    """SU2 mesh files (.su2), 2D or 3D; not one of PyGeM's handlers.

    parse and write as the PyGeM-style handlers; elements and markers kept.
    """

    extensions = [".su2"]


__all__ = ["read_mesh", "write_mesh", "read_volume_mesh", "volume_mesh_format", "VolumeMesh", "VolumeMeshFormat",
           "UnvHandler", "ElmerHandler", "KHandler", "MdpaHandler", "GmshHandler", "Su2Handler"]
