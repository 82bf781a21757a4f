"""PyGeM's OpenFOAM handler and FFD against ffdkit-cli deform on the same case, side by side.

    OMP_WAIT_POLICY=passive python3 bench/python/bench_pygem_openfoam.py \\
        --pygem PYGEM_CHECKOUT --cli build/app/cli/ffdkit-cli [--cells N] [--repeat R] [--work DIR]

PYGEM_CHECKOUT is PyGeM 1.1 (https://github.com/mathLab/PyGeM, tag v1.1: the last release with
file handlers; `git archive v1.1 pygem | tar -x -C DIR`). Its pygem/filehandler.py, openfhandler.py,
affine.py, freeform.py and params/ffdparams.py are loaded as they are, with Debian's numpy.
ffdparams.py imports OpenCASCADE and VTK at its top for a method not called here, and freeform.py
imports SciPy for scipy.special.binom only: when they are missing the script supplies empty
stand-ins and binom from math.comb.

Case: the unit cube of N^3 hexahedra (default 100: 1,030,301 points) made by openfoam_cube.py,
as an ASCII case (PyGeM's handler reads ASCII points with the count on line 19, as blockMesh
writes them) and a binary one. The deformation is tests/data/openfoam/bulge.json: a 3x3x3
Bernstein lattice on [-0.1, 1.1]^3 whose centre control point moves by (0.15, 0.1, -0.05); for
PyGeM the same lattice is box origin -0.1, length 1.2, weight (0.125, 1/12, -1/24) at [1, 1, 1].
Reports the median wall time over R runs (default 3) of:
- PyGeM: OpenFoamHandler.parse(points) + FFD.perform() + OpenFoamHandler.write (points only: PyGeM
  reads neither faces nor cells and checks nothing);
- ffdkit-cli deform -w bulge.json CASE -o OUT --timings on the ASCII and on the binary case (reads
  points, faces, owner, neighbour and boundary, checks every cell as checkMesh does, writes the
  whole case, flushed to disk), with its own split of the time.
Also the largest difference between PyGeM's written points and ffdkit's.
"""

import argparse
import importlib.util
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import time
import types

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import openfoam_cube  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def load_pygem(checkout):
    """PyGeM 1.1's OpenFoamHandler, FFD and FFDParameters, loaded from `checkout`.

    Args:
        checkout: a folder holding PyGeM 1.1's pygem/ package.

    Returns:
        (OpenFoamHandler, FFD, FFDParameters) classes.
    """
    try:
        import scipy.special  # noqa: F401
    except ImportError:
        scipy = types.ModuleType("scipy")
        special = types.ModuleType("scipy.special")
        special.binom = lambda n, k: math.comb(int(n), int(k))
        scipy.special = special
        sys.modules.update({"scipy": scipy, "scipy.special": special})
    stand_ins = {"OCC.Bnd": ["Bnd_Box"], "OCC.BRepBndLib": ["brepbndlib_Add"],
                 "OCC.BRepMesh": ["BRepMesh_IncrementalMesh"], "vtk": []}
    for name, names in stand_ins.items():
        try:
            importlib.import_module(name)
        except ImportError:
            module = types.ModuleType(name)
            for attribute in names:
                setattr(module, attribute, None)
            sys.modules[name] = module
            if "." in name:
                sys.modules.setdefault(name.split(".")[0], types.ModuleType(name.split(".")[0]))
    package = types.ModuleType("pygem")
    package.__path__ = [os.path.join(checkout, "pygem")]
    sys.modules["pygem"] = package
    params = types.ModuleType("pygem.params")
    params.__path__ = [os.path.join(checkout, "pygem", "params")]
    sys.modules["pygem.params"] = params
    modules = {}
    for name, path in (("pygem.filehandler", "filehandler.py"), ("pygem.affine", "affine.py"),
                       ("pygem.openfhandler", "openfhandler.py"), ("pygem.freeform", "freeform.py"),
                       ("pygem.params.ffdparams", "params/ffdparams.py")):
        spec = importlib.util.spec_from_file_location(name, os.path.join(checkout, "pygem", path))
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        spec.loader.exec_module(module)
        setattr(package, name.split(".")[-1], module)
        modules[name] = module
    return (modules["pygem.openfhandler"].OpenFoamHandler, modules["pygem.freeform"].FFD,
            modules["pygem.params.ffdparams"].FFDParameters)


def bulge_parameters(FFDParameters):
    """bulge.json as PyGeM's FFD parameters (weights in units of the box length)."""
    params = FFDParameters([3, 3, 3])
    params.origin_box = np.array([-0.1, -0.1, -0.1])
    params.lenght_box = np.array([1.2, 1.2, 1.2])
    params.array_mu_x[1, 1, 1] = 0.15 / 1.2
    params.array_mu_y[1, 1, 1] = 0.1 / 1.2
    params.array_mu_z[1, 1, 1] = -0.05 / 1.2
    return params


def run_pygem(classes, case, out_points):
    """One PyGeM run: parse, FFD, write. Returns (seconds of each step, deformed points)."""
    OpenFoamHandler, FFD, FFDParameters = classes
    handler = OpenFoamHandler()
    start = time.perf_counter()
    points = handler.parse(os.path.join(case, "constant", "polyMesh", "points"))
    parsed = time.perf_counter()
    ffd = FFD(bulge_parameters(FFDParameters), points)
    ffd.perform()
    deformed = time.perf_counter()
    handler.write(ffd.modified_mesh_points, out_points)
    written = time.perf_counter()
    return (parsed - start, deformed - parsed, written - deformed), ffd.modified_mesh_points


def run_cli(cli, case, out):
    """One ffdkit-cli deform run. Returns (wall seconds, its --timings line)."""
    start = time.perf_counter()
    result = subprocess.run([cli, "deform", "-w", os.path.join(ROOT, "tests", "data", "openfoam", "bulge.json"),
                             case, "-o", out, "--timings"], capture_output=True, text=True, check=True)
    wall = time.perf_counter() - start
    timings = [line for line in (result.stdout + result.stderr).splitlines() if line.startswith("timings")]
    return wall, timings[-1] if timings else ""


def ascii_points(path):
    """The points of an ASCII points file (as written by either tool)."""
    with open(path) as handle:
        text = handle.read()
    body = text[text.index("(", text.index("}")) + 1:text.rindex(")")]
    return np.array([row.split() for row in re.findall(r"\(([^()]*)\)", body)], dtype=float)


def main():
    """Command line: see the module's docstring."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--pygem", required=True, help="a checkout of PyGeM 1.1")
    parser.add_argument("--cli", default=os.path.join(ROOT, "build", "app", "cli", "ffdkit-cli"))
    parser.add_argument("--cells", type=int, default=100, help="cells per side of the cube")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--work", default="/tmp/ffdkit-bench-pygem-openfoam")
    args = parser.parse_args()

    classes = load_pygem(args.pygem)
    cases = {kind: os.path.join(args.work, f"cube{args.cells}-{kind}") for kind in ("ascii", "binary")}
    for kind, case in cases.items():
        if not os.path.exists(os.path.join(case, "constant", "polyMesh", "boundary")):
            openfoam_cube.write_case(case, args.cells, binary=kind == "binary")
    points = (args.cells + 1) ** 3
    print(f"case: {args.cells}^3 hexahedra, {points:,} points; median of {args.repeat} runs, wall time")

    pygem_out = os.path.join(args.work, "pygem-points")
    runs = [run_pygem(classes, cases["ascii"], pygem_out) for _ in range(args.repeat)]
    steps = [statistics.median(run[0][k] for run in runs) for k in range(3)]
    print(f"PyGeM 1.1 OpenFoamHandler + FFD (ASCII points): {sum(steps):.2f} s "
          f"(parse {steps[0]:.2f}, FFD {steps[1]:.2f}, write {steps[2]:.2f})")

    for kind, case in cases.items():
        out = case + "-out"
        results = [run_cli(args.cli, case, out) for _ in range(args.repeat)]
        wall = statistics.median(r[0] for r in results)
        print(f"ffdkit-cli deform ({kind} case, every cell checked, whole case written): {wall:.2f} s; "
              f"last run's {results[-1][1]}")
        if kind == "ascii":
            ffdkit_points = ascii_points(os.path.join(out, "constant", "polyMesh", "points"))
            difference = np.abs(ffdkit_points - runs[-1][1]).max()
            print(f"largest difference between PyGeM's and ffdkit's deformed points: {difference:.3g}")
        shutil.rmtree(out, ignore_errors=True)


if __name__ == "__main__":
    main()
