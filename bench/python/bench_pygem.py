"""Speed of ffdkit.pygem.FFD against the same computation in plain numpy (PyGeM's algorithm).

    PYTHONPATH=build/python OMP_WAIT_POLICY=passive python3 bench/python/bench_pygem.py [--points N] [--repeat R]

Case: N points (default 1,000,000) uniform in a rotated box 20 % larger than the FFD box, a
4x4x4 Bernstein lattice with random weights. Reports medians over R runs of the wall time and
of the process CPU time (all threads; on a shared machine CPU / 2 estimates the wall time of an
idle 2-core one):
- ffdkit.pygem.FFD(points)          the drop-in, per call: a new C-ordered result array filled by
                                    ffd.boxBernsteinDeform (points C-ordered, as numpy makes them)
- same, Fortran-ordered input       read in place too (no copy of the input either way)
- same, every result kept           no result is freed before the next call, so each one lands
                                    in fresh memory whose pages fault in on first touch (a freed
                                    result of < 32 MB is otherwise reused by malloc)
- boxBernsteinDeform, out reused    the one-pass kernel alone, writing into the same array every
                                    time (no fresh memory to fault in)
- general engine                    ffd.deformPoints: closed-form embedding + Deformer on the same
                                    lattice (what FFD(points) ran before)
- plain numpy                       box coordinates, inside test, Bernstein sums, back to world
The results are compared (max difference relative to the coordinate scale).
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


def medians(function, repeat):
    """Median wall and process CPU seconds of `repeat` calls."""
    walls, cpus = [], []
    for _ in range(repeat):
        wall, cpu = time.perf_counter(), time.process_time()
        function()
        cpus.append(time.process_time() - cpu)
        walls.append(time.perf_counter() - wall)
    return statistics.median(walls), statistics.median(cpus), walls


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--points", type=int, default=1_000_000)
    parser.add_argument("--repeat", type=int, default=11)
    parser.add_argument("--no-numpy", action="store_true", help="skip the (slow) plain numpy row")
    parser.add_argument("--samples", action="store_true",
                        help="also print every run's wall time per row (for scripts/bench.sh)")
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

    counts, displacements = params._displacements()
    box = ffd.BoxBernsteinLattice(counts, params._frame(), displacements)
    out = np.empty_like(points)
    lattice = params._lattice(params._frame(), ffd.OutsidePolicy.identity())
    general = ffd.EmbedOptions(boundaryEpsilon=1e-12)
    kept = []
    rows = [
        ("ffdkit.pygem.FFD(points), C-ordered input", lambda: params(points)),
        ("ffdkit.pygem.FFD(points), Fortran-ordered input", lambda: params(fortran)),
        ("same, every result kept (fresh memory per call)", lambda: kept.append(params(points))),
        ("  ffd.boxBernsteinDeform, out reused", lambda: ffd.boxBernsteinDeform(box, points, out=out)),
        ("  general engine: ffd.deformPoints (embed + deform)", lambda: ffd.deformPoints(lattice, fortran, general)),
    ]
    if not args.no_numpy:
        rows.append(("plain numpy (PyGeM's algorithm)", lambda: numpy_ffd(params, points)))
    inside = float(np.mean(np.all((u >= 0) & (u <= 1), axis=1)))
    print("{:,} points, 4x4x4 Bernstein, {:.0%} inside; medians of {} runs".format(args.points, inside, args.repeat))
    print("{:<52} {:>9} {:>12}".format("", "wall", "CPU (all)"))
    for name, function in rows:
        function()  # warm up (first-touch page faults, thread pool)
        repeat = args.repeat if not name.startswith("plain") else max(3, args.repeat // 4)
        wall, cpu, walls = medians(function, repeat)
        kept.clear()
        print("{:<52} {:6.2f} ms {:9.2f} ms".format(name, 1e3 * wall, 1e3 * cpu))
        if args.samples:
            print("samples ms [{}]: {}".format(name.strip(), " ".join("{:.3f}".format(1e3 * w) for w in walls)))
    result = params(points)
    scale = np.abs(points).max()
    print("max |FFD - general engine| / max |x| = {:.1e}".format(
        np.abs(result - ffd.deformPoints(lattice, fortran, general)).max() / scale))
    if not args.no_numpy:
        print("max |FFD - numpy| / max |x| = {:.1e}".format(np.abs(result - numpy_ffd(params, points)).max() / scale))


if __name__ == "__main__":
    main()
