"""PyGeM's ``FFD`` class on ffdkit's engine (and ``CFFD``, ``BFFD``, ``VFFD``: pygem_cffd.py).

A PyGeM script switches by changing its import line::

    from ffdkit.pygem import FFD      # instead of: from pygem import FFD

The class keeps PyGeM's attributes, methods, ``.prm`` parameter files (byte-compatible output)
and results; the deformation itself runs in ffdkit's C++ engine (``ffd.boxBernsteinDeform``: one
pass over the points, box coordinates then the Bernstein FFD map of Sederberg & Parry 1986,
eq. 1), in parallel and without the Python interpreter lock.

The lattice. PyGeM's box has its node (0, 0, 0) at ``box_origin``, edges of ``box_length``
along the columns of ``rotation_matrix`` = Rx(ax) Ry(ay) Rz(az) (angles ``rot_angle`` in
degrees, about the global axes, centred at ``box_origin``). ``array_mu_x[i, j, k]`` moves
control point ijk along the box's own first axis by that fraction of ``box_length[0]`` (same
for y and z). Points whose box coordinates lie in [0, 1]^3 are deformed; all others come back
unchanged. Box coordinates within 1e-12 of a face count as on it (so that rounding of the
coordinate transform never decides whether a point that lies on a face is deformed).
"""

import configparser
import copy
import os

import numpy as np

from . import _ffdkit

_ffd = _ffdkit.ffd

# Box coordinates (units of the box size) within this distance of a face count as on the face.
_FACE_TOLERANCE = 1e-12
_DEFORM_OPTIONS = _ffd.BoxBernsteinDeformOptions(faceTolerance=_FACE_TOLERANCE)


def _rotation(angles_degrees):
    """Rx(ax) Ry(ay) Rz(az) for angles in degrees (a rotation about the global axes)."""
    ax, ay, az = np.radians(np.asarray(angles_degrees, dtype=float))

    def about(axis, angle):
        c, s = np.cos(angle), np.sin(angle)
        a, b = [(1, 2), (2, 0), (0, 1)][axis]
        m = np.eye(3)
        m[a, a], m[a, b], m[b, a], m[b, b] = c, -s, s, c
        return m

    matrix = np.eye(3)
    # An angle of exactly zero contributes the identity (PyGeM skips it, so no -0.0 appears).
    for axis, angle in ((0, ax), (1, ay), (2, az)):
        if angle:
            matrix = matrix @ about(axis, angle)
    return matrix


def _linear_map(matrix):
    """A callable applying `matrix` to points stored by row, keeping the argument's shape."""

    def transform(points):
        points = np.asarray(points, dtype=float)
        return (np.atleast_2d(points) @ matrix.T).reshape(points.shape)

    return transform


class FFD:
    """Free Form Deformation of points by a Bernstein lattice box (PyGeM's ``pygem.FFD``).

    :param list n_control_points: number of control points in the x, y and z direction of
        the box. Default is [2, 2, 2].

    Attributes: ``box_length``, ``box_origin``, ``rot_angle`` (degrees), ``n_control_points``
    (setting it resets the weights to zeros), ``array_mu_x``, ``array_mu_y``, ``array_mu_z``
    (shape ``n_control_points``), ``conversion_unit`` (kept for PyGeM compatibility, unused).
    """

    reference_frame = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])

    def __init__(self, n_control_points=None):
        self.conversion_unit = 1.
        self.box_length = np.array([1., 1., 1.])
        self.box_origin = np.array([0., 0., 0.])
        self.rot_angle = np.array([0., 0., 0.])
        self.array_mu_x = None
        self.array_mu_y = None
        self.array_mu_z = None
        self.n_control_points = [2, 2, 2] if n_control_points is None else n_control_points

    # ---- geometry of the box --------------------------------------------------------------
    @property
    def n_control_points(self):
        """The number of control points in the x, y and z directions (numpy.ndarray)."""
        return self._n_control_points

    @n_control_points.setter
    def n_control_points(self, counts):
        self._n_control_points = np.array(counts)
        self.array_mu_x = np.zeros(self._n_control_points)
        self.array_mu_y = np.zeros(self._n_control_points)
        self.array_mu_z = np.zeros(self._n_control_points)

    @property
    def rotation_matrix(self):
        """Rx(rot_angle[0]) Ry(rot_angle[1]) Rz(rot_angle[2]), angles in degrees (3 x 3)."""
        return _rotation(self.rot_angle)

    @property
    def position_vertices(self):
        """The box origin and the ends of its three edges from the origin (4 x 3, by row)."""
        edges = self.rotation_matrix * np.asarray(self.box_length, dtype=float)  # R @ diag(L)
        return np.asarray(self.box_origin, dtype=float) + np.vstack([np.zeros((1, 3)), edges.T])

    @property
    def psi(self):
        """The map from physical coordinates relative to ``box_origin`` to box coordinates."""
        return _linear_map(np.diag(1.0 / np.asarray(self.box_length, dtype=float)) @ self.rotation_matrix.T)

    @property
    def inverse_psi(self):
        """The map from box coordinates to physical coordinates relative to ``box_origin``."""
        return _linear_map(self.rotation_matrix * np.asarray(self.box_length, dtype=float))

    @property
    def T(self):
        """The deformation of box coordinates: points (N x 3) in the unit cube -> deformed.

        The Bernstein polynomials are evaluated for every point given, inside the cube or not.
        """

        def t_mapping(points):
            points = np.asarray(points, dtype=float)
            lattice = self._lattice(np.eye(4), _ffd.OutsidePolicy.extrapolate())
            return _ffd.deformPoints(lattice, points)

        return t_mapping

    def reset_weights(self):
        """Set the weights (the displacements of the control points) to zeros.

        Afterwards the FFD maps every point to itself.
        """
        self.array_mu_x.fill(0.0)
        self.array_mu_y.fill(0.0)
        self.array_mu_z.fill(0.0)

    # ---- the engine -----------------------------------------------------------------------
    def _frame(self):
        frame = np.eye(4)
        frame[:3, :3] = self.rotation_matrix * np.asarray(self.box_length, dtype=float)
        frame[:3, 3] = self.box_origin
        return frame

    def _displacements(self):
        """The weights as (l*m*n, 3) displacements in box coordinates, row i + l*(j + m*k)."""
        counts = tuple(int(c) for c in self.n_control_points)
        weights = (self.array_mu_x, self.array_mu_y, self.array_mu_z)
        for name, mu in zip(("array_mu_x", "array_mu_y", "array_mu_z"), weights):
            if np.shape(mu) != counts:
                raise ValueError("{} has shape {}, expected n_control_points {}".format(
                    name, np.shape(mu), counts))
        # ffdkit's flat index i + l*(j + m*k) is numpy's Fortran order of an (l, m, n) array; the
        # box is the unit cube in lattice coordinates, so a weight is a local displacement.
        return counts, np.stack([np.asarray(mu, dtype=float).ravel(order="F") for mu in weights], axis=1)

    def _lattice(self, frame, policy):
        counts, displacements = self._displacements()
        lattice = _ffd.makeBoxLattice(counts=counts, bases=_ffd.AxisBasis.bernstein(), frame=frame,
                                      outsidePolicy=policy)
        control = lattice.controlPoints
        control += displacements
        return lattice

    def __call__(self, src_pts):
        """Deform the points `src_pts` (n_points x 3, by row); return the deformed points.

        Points inside the box (box coordinates in [0, 1]^3) are deformed, the others returned
        unchanged. The result is a new writable C-ordered array; `src_pts` is read in place
        whatever its layout. One pass in C++ without the interpreter lock
        (``ffdkit.ffd.boxBernsteinDeform``).
        """
        counts, displacements = self._displacements()
        lattice = _ffd.BoxBernsteinLattice(counts, self._frame(), displacements)
        return _ffd.boxBernsteinDeform(lattice, src_pts, _DEFORM_OPTIONS)

    def control_points(self, deformed=True):
        """The control points of the lattice in physical coordinates (n_points x 3, by row,
        index k fastest, then j, then i), displaced by the weights if `deformed`."""
        ticks = [np.linspace(0, self.box_length[a], self.n_control_points[a]) for a in range(3)]
        grid = np.meshgrid(*ticks, indexing="ij")
        local = np.stack([g.ravel() for g in grid], axis=1)
        if deformed:
            mu = np.stack([self.array_mu_x.ravel(), self.array_mu_y.ravel(), self.array_mu_z.ravel()], axis=1)
            local = local + mu * np.asarray(self.box_length, dtype=float)
        return local @ self.rotation_matrix.T + self.box_origin

    def reflect(self, axis=0, in_place=True):
        """Mirror the lattice at its face opposite to the origin across `axis` (0, 1 or 2):
        2n-1 control points and twice the box length along `axis`; the weights along `axis`
        change sign in the mirrored half, the others are copied. The face must carry no weight
        along `axis`. Returns the new FFD if `in_place` is False, else None."""
        if axis not in (0, 1, 2):
            raise ValueError("The axis has to be 0, 1, or 2. Current value {}.".format(axis))
        weights = (self.array_mu_x, self.array_mu_y, self.array_mu_z)
        if np.count_nonzero(np.take(weights[axis], -1, axis=axis)) != 0:
            raise RuntimeError(
                "If you want to reflect the FFD bounding box along axis {} you can not diplace "
                "the control points in the symmetry plane along that axis.".format(axis))
        target = self if in_place else copy.deepcopy(self)
        target.n_control_points[axis] = 2 * target.n_control_points[axis] - 1
        target.box_length[axis] *= 2
        mirrored = []
        for component, mu in enumerate(weights):
            sign = -1.0 if component == axis else 1.0
            tail = np.flip(mu, axis).take(np.arange(1, mu.shape[axis]), axis=axis)
            mirrored.append(np.concatenate([mu, sign * tail], axis=axis))
        target.array_mu_x, target.array_mu_y, target.array_mu_z = mirrored
        return None if in_place else target

    # ---- parameter files --------------------------------------------------------------------
    def read_parameters(self, filename='parameters.prm'):
        """Read a PyGeM ``.prm`` parameter file. A missing file is created with the current
        parameters instead (PyGeM's behaviour)."""
        if not isinstance(filename, str):
            raise TypeError("filename must be a string")
        if not os.path.isfile(filename):
            self.write_parameters(filename)
            return
        config = configparser.RawConfigParser()
        config.read(filename)
        box = 'Box info'
        for a, letter in enumerate('xyz'):
            self.n_control_points[a] = config.getint(box, 'n control points ' + letter)
            self.box_length[a] = config.getfloat(box, 'box length ' + letter)
            self.box_origin[a] = config.getfloat(box, 'box origin ' + letter)
            self.rot_angle[a] = config.getfloat(box, 'rotation angle ' + letter)
        arrays = []
        for letter in 'xyz':
            mu = np.zeros(self.n_control_points)
            for line in config.get('Parameters weights', 'parameter ' + letter).split('\n'):
                fields = line.split()
                mu[tuple(int(f) for f in fields[0:3])] = float(fields[3])
            arrays.append(mu)
        self.array_mu_x, self.array_mu_y, self.array_mu_z = arrays

    def write_parameters(self, filename='parameters.prm'):
        """Write the parameters as a PyGeM ``.prm`` file (the same bytes PyGeM writes).

        :param str filename: the file to write (default ``parameters.prm``).
        :raises TypeError: if `filename` is not a string.
        """
        if not isinstance(filename, str):
            raise TypeError("filename must be a string")
        text = _PRM_BOX_HEAD
        for title, values in zip(_PRM_BOX_SECTIONS, (self.n_control_points, self.box_length,
                                                     self.box_origin, self.rot_angle)):
            key, comment = title
            text += comment
            text += ''.join('{} {}: {}\n'.format(key, letter, str(values[a])) for a, letter in enumerate('xyz'))
        text += _PRM_WEIGHTS_HEAD
        for letter, mu in zip('xyz', (self.array_mu_x, self.array_mu_y, self.array_mu_z)):
            text += _PRM_WEIGHTS_COMMENT.format(letter)
            text += '\nparameter {}:'.format(letter)
            indent = 1
            counts = self.n_control_points
            for i in range(counts[0]):
                for j in range(counts[1]):
                    for k in range(counts[2]):
                        text += '{}{}   {}   {}   {}\n'.format(' ' * indent, i, j, k, str(mu[i][j][k]))
                        indent = 13
        with open(filename, 'w') as f:
            f.write(text)

    def __str__(self):
        lines = [
            'conversion_unit = {}'.format(self.conversion_unit),
            'n_control_points = {}\n'.format(self.n_control_points),
            'box_length = {}'.format(self.box_length),
            'box_origin = {}'.format(self.box_origin),
            'rot_angle  = {}'.format(self.rot_angle),
            '\narray_mu_x =\n{}'.format(self.array_mu_x),
            '\narray_mu_y =\n{}'.format(self.array_mu_y),
            '\narray_mu_z =\n{}'.format(self.array_mu_z),
            '\nrotation_matrix = \n{}'.format(self.rotation_matrix),
            '\nposition_vertices = {}'.format(self.position_vertices),
        ]
        return '\n'.join(lines) + '\n'


# The fixed text of a .prm file, in PyGeM's layout.
_PRM_BOX_HEAD = '\n[Box info]\n# This section collects all the properties of the FFD bounding box.\n'
_PRM_BOX_SECTIONS = (
    ('n control points',
     '\n# n control points indicates the number of control points in each direction (x, y, z).\n'
     '# For example, to create a 2 x 3 x 2 grid, use the following: n control points: 2, 3, 2\n'),
    ('box length',
     '\n# box length indicates the length of the FFD bounding box along the three canonical directions (x, y, z).\n'
     '# It uses the local coordinate system.\n'
     '# For example to create a 2 x 1.5 x 3 meters box use the following: box length: 2.0, 1.5, 3.0\n'),
    ('box origin',
     '\n# box origin indicates the x, y, and z coordinates of the origin of the FFD bounding box. That is center of\n'
     '# rotation of the bounding box. It corresponds to the point coordinates with position [0][0][0].\n'
     '# See section "Parameters weights" for more details.\n'
     '# For example, if the origin is equal to 0., 0., 0., use the following: box origin: 0., 0., 0.\n'),
    ('rotation angle',
     '\n# rotation angle indicates the rotation angle around the x, y, and z axis of the FFD bounding box in degrees.\n'
     '# The rotation is done with respect to the box origin.\n'
     '# For example, to rotate the box by 2 deg along the z direction, use the following: rotation angle: 0., 0., 2.\n'),
)
_PRM_WEIGHTS_HEAD = (
    '\n\n[Parameters weights]\n'
    '# This section describes the weights of the FFD control points.\n'
    '# We adopt the following convention:\n'
    '# For example with a 2x2x2 grid of control points we have to fill a 2x2x2 matrix of weights.\n'
    '# If a weight is equal to zero you can discard the line since the default is zero.\n'
    '#\n'
    '# | x index | y index | z index | weight |\n'
    '#  --------------------------------------\n'
    '# |    0    |    0    |    0    |  1.0   |\n'
    '# |    0    |    1    |    1    |  0.0   | --> you can erase this line without effects\n'
    '# |    0    |    1    |    0    | -2.1   |\n'
    '# |    0    |    0    |    1    |  3.4   |\n'
)
_PRM_WEIGHTS_COMMENT = '\n# parameter {0} collects the displacements along {0}, normalized with the box length {0}.'

# PyGeM's constrained classes, defined on FFD above (imported last: they subclass it).
from .pygem_cffd import BFFD, CFFD, VFFD  # noqa: E402,F401
