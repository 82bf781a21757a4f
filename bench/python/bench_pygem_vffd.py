"""ffdkit.pygem.VFFD against PyGeM's own VFFD on the same closed mesh, side by side.

    PYTHONPATH=build/python OMP_WAIT_POLICY=passive python3 bench/python/bench_pygem_vffd.py \\
        --pygem PYGEM_CHECKOUT [--vertices N] [--repeat R]

PYGEM_CHECKOUT is a clone of https://github.com/mathLab/PyGeM; its pygem/ffd.py, cffd.py, vffd.py,
deformation.py and utils.py are loaded as they are. PyGeM imports SciPy only for
scipy.special.binom (FFD) and two scipy.optimize names CFFD never calls; when SciPy is missing the
script supplies binom from math.comb and empty stand-ins for the other two.

Case: a closed UV sphere of about N vertices (default 100,000) inside the unit box, a 3x3x3
lattice with random weights (normal, deviation 0.05), target volume 5 % above the rest volume. Reports the median wall time of
adjust_control_points + one deformation over R runs (default 3) and the relative volume error
each reaches (with the per-axis split the volume is linear in the moving weights: PyGeM fits that
linear map from 3x3x3 + 1 deformations per axis, ffdkit computes it in one adjoint pass).
"""

import argparse
import importlib.util
import math
import statistics
import sys
import time
import types

import numpy as np


def load_pygem(checkout):
    try:
        import scipy.special  # noqa: F401
        import scipy.optimize  # noqa: F401
    except ImportError:
        scipy = types.ModuleType("scipy")
        special = types.ModuleType("scipy.special")
        special.binom = lambda n, k: math.comb(int(n), int(k))
        optimize = types.ModuleType("scipy.optimize")
        optimize.LinearConstraint = optimize.differential_evolution = None
        scipy.special, scipy.optimize = special, optimize
        sys.modules.update({"scipy": scipy, "scipy.special": special, "scipy.optimize": optimize})
    package = types.ModuleType("pygem")
    package.__path__ = [checkout + "/pygem"]
    sys.modules["pygem"] = package
    modules = {}
    for name in ("deformation", "utils", "ffd", "cffd", "vffd"):
        spec = importlib.util.spec_from_file_location("pygem." + name, f"{checkout}/pygem/{name}.py")
        module = importlib.util.module_from_spec(spec)
        sys.modules["pygem." + name] = module
        spec.loader.exec_module(module)
        modules[name] = module
        if name == "deformation":
            package.Deformation = module.Deformation
        if name == "ffd":
            package.FFD = module.FFD
        if name == "cffd":
            package.CFFD = module.CFFD
    return modules["vffd"].VFFD


def sphere(vertices):
    rings = max(4, int(math.sqrt(vertices / 2)))
    segments = 2 * rings
    theta = np.pi * np.arange(1, rings) / rings
    phi = 2 * np.pi * np.arange(segments) / segments
    t, p = np.meshgrid(theta, phi, indexing="ij")
    ring = np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], axis=-1).reshape(-1, 3)
    points = 0.5 + 0.3 * np.vstack([[0, 0, 1], ring, [0, 0, -1]])
    n = len(points)

    def at(r, s):
        return 1 + (r - 1) * segments + s % segments

    s = np.arange(segments)
    tris = [np.stack([np.zeros(segments, int), at(1, s), at(1, s + 1)], axis=1)]
    for r in range(1, rings - 1):
        tris.append(np.stack([at(r, s), at(r + 1, s), at(r + 1, s + 1)], axis=1))
        tris.append(np.stack([at(r, s), at(r + 1, s + 1), at(r, s + 1)], axis=1))
    tris.append(np.stack([np.full(segments, n - 1), at(rings - 1, s + 1), at(rings - 1, s)], axis=1))
    return points, np.vstack(tris)


def run(VFFD, points, triangles, weights, volume, repeat):
    times, errors = [], []
    target = np.array([6 * volume * 1.05])
    for _ in range(repeat):
        vffd = VFFD(triangles, target, [3, 3, 3])
        vffd.array_mu_x, vffd.array_mu_y, vffd.array_mu_z = (w.copy() for w in weights)
        start = time.perf_counter()
        vffd.adjust_control_points(points)
        deformed = vffd(points)
        times.append(time.perf_counter() - start)
        errors.append(abs(vffd.fun(deformed)[0] - target[0]) / target[0])
    return statistics.median(times), max(errors)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pygem", required=True, help="a clone of mathLab/PyGeM")
    parser.add_argument("--vertices", type=int, default=100000)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    points, triangles = sphere(args.vertices)
    a, b, c = (points[triangles[:, k]] for k in range(3))
    volume = np.sum(np.einsum("ij,ij->i", a, np.cross(b, c))) / 6
    rng = np.random.default_rng(0)
    weights = [0.05 * rng.standard_normal((3, 3, 3)) for _ in range(3)]
    from ffdkit.pygem import VFFD as OurVFFD
    TheirVFFD = load_pygem(args.pygem)
    print(f"closed sphere: {len(points)} vertices, {len(triangles)} triangles; 3x3x3 lattice")
    for name, cls in (("ffdkit.pygem.VFFD", OurVFFD), ("PyGeM VFFD", TheirVFFD)):
        seconds, error = run(cls, points, triangles, weights, volume, args.repeat)
        print(f"{name:18s} median {seconds * 1e3:10.1f} ms   relative volume error {error:.2e}")


if __name__ == "__main__":
    main()
