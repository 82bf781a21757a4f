"""Independent numpy evaluators the Python tests compare ffdkit against (no ffdkit code)."""

from math import comb

import numpy as np


def bernstein(degree, t):
    """B_i(t) = C(n, i) t^i (1 - t)^(n - i), i = 0..n, for an array t: shape t.shape + (n + 1,)
    (Sederberg & Parry 1986, eq. 1), by the explicit formula."""
    t = np.asarray(t, dtype=float)[..., None]
    i = np.arange(degree + 1)
    binomials = np.array([comb(degree, k) for k in i], dtype=float)
    return binomials * t ** i * (1.0 - t) ** (degree - i)


def bernstein_ffd(control, counts, uvw):
    """X(u,v,w) = sum_ijk B_i(u) B_j(v) B_k(w) P_ijk for a Bernstein lattice whose control points
    (l*m*n x 3) are stored with flat index i + l*(j + m*k)."""
    l, m, n = counts
    grid = np.asarray(control, dtype=float).reshape((l, m, n, 3), order="F")
    uvw = np.atleast_2d(uvw)
    bu, bv, bw = bernstein(l - 1, uvw[:, 0]), bernstein(m - 1, uvw[:, 1]), bernstein(n - 1, uvw[:, 2])
    return np.einsum("pi,pj,pk,ijkc->pc", bu, bv, bw, grid)


def apply_frame(frame, points):
    """World = frame @ local for points by row (frame 4 x 4)."""
    return np.asarray(points) @ frame[:3, :3].T + frame[:3, 3]


def rotation(axis, degrees):
    """Counter-clockwise rotation about a global axis (right-hand rule)."""
    c, s = np.cos(np.radians(degrees)), np.sin(np.radians(degrees))
    a, b = [(1, 2), (2, 0), (0, 1)][axis]
    r = np.eye(3)
    r[a, a], r[a, b], r[b, a], r[b, b] = c, -s, s, c
    return r
