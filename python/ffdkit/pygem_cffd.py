"""PyGeM's constrained FFD classes (``CFFD``, ``BFFD``, ``VFFD``) on ffdkit's engine.

Import them from ``ffdkit.pygem`` (``from ffdkit.pygem import CFFD, BFFD, VFFD``). Constructors,
attributes (``fun``, ``fixval``, ``ffd_mask``, ``fun_mask``, ``triangles``, the FFD attributes)
and calls (``adjust_control_points(src_pts)``, ``ffd(src_pts)``, ``__call__``) are PyGeM's.

What ``adjust_control_points`` does is PyGeM's algorithm with exact derivatives. PyGeM splits
the gap ``fixval - fun(ffd(src_pts))`` over the axes by ``fun_mask`` (row r of it, normalised to
sum 1, says which share of constraint r each axis closes); for each axis it moves only that
axis's free weights (``ffd_mask[..., axis]``) by the least-norm change that meets the constraints
the axis carries, from a linear map it fits to ``fun`` at random weights. Here:

- ``CFFD`` (any ``fun``) takes the derivative of ``fun(ffd(src_pts))`` with respect to the free
  weights by finite differences and repeats the least-norm step until the constraints hold to
  1e-12 relative (one step for the affine functions PyGeM's docstring asks for; a nonlinear
  ``fun`` converges instead of stopping at its linearisation);
- ``VFFD`` meets the volume of a closed surface with ffdkit's Newton solver
  (``ffdkit.ffd.ShapeConstraints.keepVolume``, exact gradients) to 1e-12 relative. With PyGeM's
  per-axis split the volume is linear in the moving weights (a determinant is linear in each
  coordinate column), so one step meets it; a surface that is not closed falls back to the
  finite-difference path;
- ``BFFD`` keeps the mean of the points (linear: one step).
"""

import numpy as np

from . import _ffdkit
from .pygem import FFD

_ffd = _ffdkit.ffd

_TOLERANCE = 1e-12  # relative residual at which adjust_control_points stops
_MAX_STEPS = 30
_STEP = 1e-3  # finite-difference step of the weights (exact for affine functions)


class CFFD(FFD):
    """Constrained Free Form Deformation: FFD whose weights are adjusted so that
    ``fun(ffd(src_pts)) = fixval`` (PyGeM's ``pygem.CFFD``).

    :param numpy.ndarray fixval: the values c of the constraints F(x) = c (length n_cons).
    :param callable fun: F, taking the deformed points (n_points x 3) and returning n_cons values.
    :param list n_control_points: control points along x, y, z. Default [2, 2, 2].
    :param numpy.ndarray ffd_mask: (n_x, n_y, n_z, 3) bools: which weights may move, per axis.
        Default all True.
    :param numpy.ndarray fun_mask: (n_cons, 3) bools: which axes each constraint is met along.
        Default all True (each axis closes a third of the gap).
    """

    def __init__(self, fixval, fun, n_control_points=None, ffd_mask=None, fun_mask=None):
        super().__init__(n_control_points)
        if ffd_mask is None:
            self.ffd_mask = np.full((*self.n_control_points, 3), True, dtype=bool)
        else:
            self.ffd_mask = ffd_mask
        self.num_cons = len(fixval)
        self.fun = fun
        self.fixval = fixval
        if fun_mask is None:
            self.fun_mask = np.full((self.num_cons, 3), True, dtype=bool)
        else:
            self.fun_mask = fun_mask

    def ffd(self, src_pts):
        """Classic FFD of `src_pts` (the deformation with the current weights).

        :param numpy.ndarray src_pts: the points to deform (n x 3).
        :return: the deformed points.
        """
        return super().__call__(src_pts)

    def adjust_control_points(self, src_pts):
        """Adjust the weights so that fun(ffd(src_pts)) = fixval.

        :param numpy.ndarray src_pts: the points whose deformation is constrained (n x 3).
        :raises ValueError: an axis's constraints cannot be met with its free weights.
        """
        src_pts = np.asarray(src_pts, dtype=float)
        fun_mask = np.asarray(self.fun_mask, dtype=bool)
        share = fun_mask.astype(float) / np.sum(fun_mask, axis=1, keepdims=True)
        fixval = np.asarray(self.fixval, dtype=float).reshape(-1)
        gap = fixval - np.asarray(self.fun(self.ffd(src_pts)), dtype=float).reshape(-1)
        for axis in range(3):
            rows = fun_mask[:, axis]
            if not np.any(rows):
                continue
            current = np.asarray(self.fun(self.ffd(src_pts)), dtype=float).reshape(-1)
            target = (current + share[:, axis] * gap)[rows]
            self._meet(src_pts, axis, rows, target)

    # ---- PyGeM's parameter vector (kept for scripts that use it) ------------------------------
    def _save_parameters(self):
        """The weights as one vector, (n_x, n_y, n_z, 3) flattened (PyGeM's order)."""
        tmp = np.zeros([*self.n_control_points, 3])
        tmp[:, :, :, 0] = self.array_mu_x
        tmp[:, :, :, 1] = self.array_mu_y
        tmp[:, :, :, 2] = self.array_mu_z
        return tmp.reshape(-1)

    def _load_parameters(self, tmp):
        """Set the weights from a vector made by _save_parameters."""
        tmp = np.asarray(tmp, dtype=float).reshape(*self.n_control_points, 3)
        self.array_mu_x = tmp[:, :, :, 0].copy()
        self.array_mu_y = tmp[:, :, :, 1].copy()
        self.array_mu_z = tmp[:, :, :, 2].copy()

    # ---- the solve ------------------------------------------------------------------------------
    def _weights(self, axis):
        return (self.array_mu_x, self.array_mu_y, self.array_mu_z)[axis]

    def _meet(self, src_pts, axis, rows, target):
        """Least-norm change of the free weights along `axis` meeting fun(...)[rows] = target."""
        self._meet_by_differences(src_pts, axis, rows, target)

    def _meet_by_differences(self, src_pts, axis, rows, target):
        free = np.asarray(self.ffd_mask, dtype=bool)[..., axis]
        indices = np.flatnonzero(free)
        scale = np.abs(target) + 1.0
        mu = self._weights(axis)
        mu = np.array(mu, dtype=float)
        self._set_weights(axis, mu)

        def values():
            return np.asarray(self.fun(self.ffd(src_pts)), dtype=float).reshape(-1)[rows]

        for _ in range(_MAX_STEPS):
            base = values()
            residual = target - base
            if np.all(np.abs(residual) <= _TOLERANCE * scale):
                return
            if indices.size == 0:
                break
            jacobian = np.empty((residual.size, indices.size))
            flat = mu.reshape(-1)
            for column, index in enumerate(indices):
                saved = flat[index]
                flat[index] = saved + _STEP
                jacobian[:, column] = (values() - base) / _STEP
                flat[index] = saved
            step, *_ = np.linalg.lstsq(jacobian, residual, rcond=None)  # least norm
            if not np.all(np.isfinite(step)):
                break
            flat[indices] += step
        residual = target - values()
        if not np.all(np.abs(residual) <= 1e-8 * scale):
            raise ValueError("CFFD: the constraints along axis {} cannot be met with its free weights "
                             "(largest residual {:.3g})".format(axis, np.max(np.abs(residual))))

    def _set_weights(self, axis, mu):
        if axis == 0:
            self.array_mu_x = mu
        elif axis == 1:
            self.array_mu_y = mu
        else:
            self.array_mu_z = mu


class BFFD(CFFD):
    """Barycentre Free Form Deformation: keeps the mean of the points at `fixval` (PyGeM's
    ``pygem.BFFD``); axis i meets the i-th coordinate of the mean.

    :param numpy.ndarray fixval: the target barycentre (3,).
    :param list n_control_points: control points along x, y, z. Default [2, 2, 2].
    :param numpy.ndarray ffd_mask: (n_x, n_y, n_z, 3) bools, which weights may move.
    """

    def __init__(self, fixval=None, n_control_points=None, ffd_mask=None):
        super().__init__(fixval, None, n_control_points, ffd_mask, None)

        def linfun(x):
            return np.mean(x.reshape(-1, 3), axis=0)

        self.fun = linfun
        self.fixval = fixval
        self.fun_mask = np.array([[True, False, False], [False, True, False], [False, False, True]])


class VFFD(CFFD):
    """Volumetric Free Form Deformation: keeps the volume of a closed triangle surface
    (PyGeM's ``pygem.VFFD``). ``fun`` is PyGeM's: the sum over triangles of det[a, b, c]
    (six times the enclosed volume).

    :param numpy.ndarray triangles: (n_triangles, 3) vertex indices into the points.
    :param numpy.ndarray fixval: the target of ``fun`` (one value).
    :param list n_control_points: control points along x, y, z. Default [2, 2, 2].
    :param numpy.ndarray ffd_mask: (n_x, n_y, n_z, 3) bools, which weights may move.
    """

    def __init__(self, triangles, fixval, n_control_points=None, ffd_mask=None):
        super().__init__(fixval, None, n_control_points, ffd_mask, None)
        self.triangles = triangles

        def volume_inn(x):
            return _volume(x, self.triangles)

        self._volume_fun = volume_inn
        self.fun = volume_inn
        self.fixval = fixval
        self.fun_mask = np.array([[True, True, True]])

    def _meet(self, src_pts, axis, rows, target):
        if self.fun is not self._volume_fun or src_pts.ndim != 2 or src_pts.shape[1] != 3:
            return self._meet_by_differences(src_pts, axis, rows, target)
        try:
            self._meet_volume(src_pts, axis, float(target[0]))
        except _ffdkit.ConstraintError as error:
            if "closed" not in str(error):
                raise ValueError("VFFD: " + str(error)) from error
            self._meet_by_differences(src_pts, axis, rows, target)

    def _meet_volume(self, src_pts, axis, target):
        """Newton on the Lagrange system in ffdkit's engine: the volume met to 1e-12."""
        counts = tuple(int(c) for c in self.n_control_points)
        lattice = self._lattice(self._frame(), _ffd.OutsidePolicy.identity())
        constraints = _ffd.ShapeConstraints(lattice, src_pts)
        free = np.zeros((lattice.pointCount, 3), dtype=bool)
        free[:, axis] = np.asarray(self.ffd_mask, dtype=bool)[..., axis].ravel(order="F")
        constraints.setFreeControls(free)
        # PyGeM's fun is sum det[a, b, c] = 6 V.
        constraints.keepVolume(np.asarray(self.triangles), target / 6.0, evaluation="per_vertex")  # one solve
        result = constraints.solve(lattice)
        change = result.change[:, axis].reshape(counts, order="F")
        self._set_weights(axis, np.asarray(self._weights(axis), dtype=float) + change)


def _volume(x, triangles):
    """PyGeM's volume function: sum over triangles of det[a, b, c] (6 x the enclosed volume)."""
    x = np.asarray(x).reshape(-1, 3)
    mesh = x[triangles]
    return np.array([np.sum(np.linalg.det(mesh))])
