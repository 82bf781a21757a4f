"""Speed of ffdkit.pygem.FFD against the same computation in plain numpy (PyGeM's algorithm).

    PYTHONPATH=build/python OMP_WAIT_POLICY=passive python3 bench/python/bench_pygem.py [--points N] [--repeat R]

Case: N points (default 1,000,000) uniform in a rotated box 20 % larger than the FFD box, a
4x4x4 Bernstein lattice with random weights. Reports medians over R runs (wall time):
- ffdkit.pygem.FFD(points)          the drop-in, per call: embed + deform (points C-ordered, as
                                    numpy makes them; they are copied once to Fortran order)
- same, Fortran-ordered input       no copy of the input
- embed only / deform only          ffdkit.ffd.embed, Deformer.deform (the engine's two halves)
- plain numpy                       box coordinates, inside test, Bernstein sums, back to world
The two results are compared (max difference relative to the coordinate scale).
"""

import argparse
import statistics
import time
from math import comb

import numpy as np

from ffdkit import ffd
from ffdkit.pygem import FFD


def numpy_ffd(params, points):
    """PyGeM's FFD in plain numpy (no ffdkit): the reference computation being timed."""
    rotation = params.rotation_matrix
    length = np.asarray(params.box_length, dtype=float)
    u = ((points - params.box_origin) @ rotation) / length
    inside = np.all((u >= 0.0) & (u <= 1.0), axis=1)
    ui = u[inside]
    l, m, n = params.array_mu_x.shape
    basis = []
    for axis, count in enumerate((l, m, n)):
        t = ui[:, axis]
        basis.append([comb(count - 1, i) * t ** i * (1 - t) ** (count - 1 - i) for i in range(count)])
    shift = np.zeros_like(ui)
    for j in range(m):
        for k in range(n):
            byz = basis[1][j] * basis[2][k]
            for i in range(l):
                b = basis[0][i] * byz
                shift[:, 0] += b * params.array_mu_x[i, j, k]
                shift[:, 1] += b * params.array_mu_y[i, j, k]
                shift[:, 2] += b * params.array_mu_z[i, j, k]
    out = points.copy()
    out[inside] = params.box_origin + ((ui + shift) * length) @ rotation.T
    return out


def median_seconds(function, repeat):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--points", type=int, default=1_000_000)
    parser.add_argument("--repeat", type=int, default=11)
    args = parser.parse_args()

    rng = np.random.default_rng(1)
    params = FFD([4, 4, 4])
    params.box_origin = np.array([-0.5, 0.2, 0.1])
    params.box_length = np.array([2.0, 1.0, 1.5])
    params.rot_angle = np.array([10.0, -20.0, 30.0])
    for mu in (params.array_mu_x, params.array_mu_y, params.array_mu_z):
        mu[:] = 0.2 * rng.standard_normal(mu.shape)
    u = rng.random((args.points, 3)) * 1.2 - 0.1
    points = params.box_origin + (u * params.box_length) @ params.rotation_matrix.T  # C-ordered
    fortran = np.asfortranarray(points)

    lattice = params._lattice(params._frame(), ffd.OutsidePolicy.identity())
    embedding = ffd.embed(lattice, fortran)
    deformer = ffd.Deformer(embedding)
    rows = [
        ("ffdkit.pygem.FFD(points), C-ordered input", lambda: params(points)),
        ("ffdkit.pygem.FFD(points), Fortran-ordered input", lambda: params(fortran)),
        ("  engine: ffd.embed (closed form)", lambda: ffd.embed(lattice, fortran)),
        ("  engine: Deformer.deform", lambda: deformer.deform(lattice, fortran)),
        ("plain numpy (PyGeM's algorithm)", lambda: numpy_ffd(params, points)),
    ]
    print("{:,} points, 4x4x4 Bernstein, {:.0%} inside; medians of {} runs".format(
        args.points, float(np.mean(embedding.statuses() == 0)), args.repeat))
    for name, function in rows:
        function()  # warm up (first-touch page faults, thread pool)
        repeat = args.repeat if not name.startswith("plain") else max(3, args.repeat // 4)
        print("{:<50} {:9.2f} ms".format(name, 1e3 * median_seconds(function, repeat)))
    difference = np.abs(params(points) - numpy_ffd(params, points)).max() / np.abs(points).max()
    print("max |ffdkit - numpy| / max |x| = {:.1e}".format(difference))


if __name__ == "__main__":
    main()
