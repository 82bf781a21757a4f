"""An OpenFOAM case of a unit cube of n^3 hexahedra, as blockMesh writes it, made with numpy.

    python3 bench/python/openfoam_cube.py CASE N [--ascii]

The case is the one bench/meshio/openfoam_bench.cpp makes (the same points, faces, owner,
neighbour and boundary, in the same order): points x fastest, internal faces by owner then
+x, +y, +z, the boundary faces of one patch after them. Binary (`arch "LSB;label=32;scalar=64"`)
by default, or ASCII with the header of blockMesh's files, so that the point count is on line 19
of `points` as PyGeM's OpenFOAM handler expects. Also `system/controlDict`, `fvSchemes` and
`fvSolution`, so that OpenFOAM's checkMesh runs on the case.
"""

import argparse
import os

import numpy as np

BANNER = """/*--------------------------------*- C++ -*----------------------------------*\\
| =========                 |                                                 |
| \\\\      /  F ield         | OpenFOAM: The Open Source CFD Toolbox           |
|  \\\\    /   O peration     | Version:                                        |
|   \\\\  /    A nd           | Website:  www.openfoam.com                      |
|    \\\\/     M anipulation  |                                                 |
\\*---------------------------------------------------------------------------*/
"""
RULE = "// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n\n"


def header(class_name, obj, binary, location="constant/polyMesh"):
    """The banner and FoamFile dictionary of one file.

    Args:
        class_name: the FoamFile class (vectorField, faceCompactList, labelList, ...).
        obj: the object name (points, faces, ...).
        binary: whether the file's lists are binary.
        location: the FoamFile location entry.

    Returns:
        The text up to the list's size line.
    """
    arch = '    arch        "LSB;label=32;scalar=64";\n' if binary else ""
    return (BANNER + "FoamFile\n{\n    version     2.0;\n    format      " + ("binary" if binary else "ascii") +
            ";\n    class       " + class_name + ";\n" + arch + '    location    "' + location +
            '";\n    object      ' + obj + ";\n}\n" + RULE + "\n")


def cube(n):
    """The points, faces (4 point indices each), owner and neighbour of the n^3 cube.

    Args:
        n: cells per side.

    Returns:
        (points (#P, 3) float64, faces (#F, 4) int32, owner (#F,) int32, neighbour (#I,) int32).
    """
    m = n + 1
    k, j, i = np.meshgrid(np.arange(m), np.arange(m), np.arange(m), indexing="ij")
    points = np.stack([i.ravel() / n, j.ravel() / n, k.ravel() / n], axis=1)

    def point(i, j, k):
        return (i + m * (j + m * k)).astype(np.int32)

    def cell(i, j, k):
        return (i + n * (j + n * k)).astype(np.int32)

    k, j, i = [a.ravel() for a in np.meshgrid(np.arange(n), np.arange(n), np.arange(n), indexing="ij")]
    c = cell(i, j, k)
    # Internal faces of each cell in the order +x, +y, +z (those that exist), cell by cell.
    quads = np.stack([
        np.stack([point(i + 1, j, k), point(i + 1, j + 1, k), point(i + 1, j + 1, k + 1), point(i + 1, j, k + 1)], 1),
        np.stack([point(i, j + 1, k), point(i, j + 1, k + 1), point(i + 1, j + 1, k + 1), point(i + 1, j + 1, k)], 1),
        np.stack([point(i, j, k + 1), point(i + 1, j, k + 1), point(i + 1, j + 1, k + 1), point(i, j + 1, k + 1)], 1),
    ], 1)
    neighbours = np.stack([cell(i + 1, j, k), cell(i, j + 1, k), cell(i, j, k + 1)], 1)
    exists = np.stack([i + 1 < n, j + 1 < n, k + 1 < n], 1)
    internal = quads[exists]
    owner_internal = np.repeat(c, exists.sum(1))
    neighbour = neighbours[exists]
    # Boundary faces: for each (a, b), the faces at x = 0, x = 1, y = 0, y = 1, z = 0, z = 1.
    a, b = [x.ravel() for x in np.meshgrid(np.arange(n), np.arange(n), indexing="ij")]
    z = np.zeros_like(a)
    full = np.full_like(a, n)
    boundary = np.stack([
        np.stack([point(z, a, b), point(z, a, b + 1), point(z, a + 1, b + 1), point(z, a + 1, b)], 1),
        np.stack([point(full, a, b), point(full, a + 1, b), point(full, a + 1, b + 1), point(full, a, b + 1)], 1),
        np.stack([point(a, z, b), point(a + 1, z, b), point(a + 1, z, b + 1), point(a, z, b + 1)], 1),
        np.stack([point(a, full, b), point(a, full, b + 1), point(a + 1, full, b + 1), point(a + 1, full, b)], 1),
        np.stack([point(a, b, z), point(a, b + 1, z), point(a + 1, b + 1, z), point(a + 1, b, z)], 1),
        np.stack([point(a, b, full), point(a + 1, b, full), point(a + 1, b + 1, full), point(a, b + 1, full)], 1),
    ], 1).reshape(-1, 4)
    owner_boundary = np.stack([cell(z, a, b), cell(full - 1, a, b), cell(a, z, b), cell(a, full - 1, b), cell(a, b, z),
                               cell(a, b, full - 1)], 1).ravel()
    faces = np.concatenate([internal, boundary])
    owner = np.concatenate([owner_internal, owner_boundary]).astype(np.int32)
    return points, faces, owner, neighbour.astype(np.int32)


def write_list(out, values, binary, ascii_item):
    """One list: its size, then the items raw (binary) or one per line (ASCII)."""
    out.write(f"{len(values)}\n(".encode())
    if binary:
        out.write(np.ascontiguousarray(values).tobytes())
        out.write(b")\n")
    else:
        out.write(b"\n")
        for start in range(0, len(values), 1 << 16):
            out.write("".join(ascii_item(v) for v in values[start:start + (1 << 16)].tolist()).encode())
        out.write(b")\n")


def write_case(root, n, binary=True):
    """Writes the case folder `root` holding the n^3 cube.

    Args:
        root: the case folder (made when missing).
        n: cells per side.
        binary: binary lists (else ASCII, as blockMesh writes them).
    """
    points, faces, owner, neighbour = cube(n)
    mesh = os.path.join(root, "constant", "polyMesh")
    os.makedirs(mesh, exist_ok=True)
    os.makedirs(os.path.join(root, "system"), exist_ok=True)
    for name, body in (("controlDict", "application blockMesh;\nstartFrom startTime;\nstartTime 0;\nstopAt endTime;\n"
                                       "endTime 1;\ndeltaT 1;\nwriteControl timeStep;\nwriteInterval 1;\n"),
                       ("fvSchemes", "ddtSchemes {}\ngradSchemes {}\ndivSchemes {}\nlaplacianSchemes {}\n"
                                     "interpolationSchemes {}\nsnGradSchemes {}\n"),
                       ("fvSolution", "")):
        with open(os.path.join(root, "system", name), "w") as out:
            out.write(header("dictionary", name, False, "system") + body)
    with open(os.path.join(mesh, "points"), "wb") as out:
        out.write(header("vectorField", "points", binary).encode())
        write_list(out, points, binary, lambda p: "(%.10g %.10g %.10g)\n" % tuple(p))
    with open(os.path.join(mesh, "faces"), "wb") as out:
        if binary:
            out.write(header("faceCompactList", "faces", True).encode())
            write_list(out, np.arange(0, 4 * len(faces) + 1, 4, dtype=np.int32), True, None)
            write_list(out, faces.ravel(), True, None)
        else:
            out.write(header("faceList", "faces", False).encode())
            write_list(out, faces, False, lambda f: "4(%d %d %d %d)\n" % tuple(f))
    for name, values in (("owner", owner), ("neighbour", neighbour)):
        with open(os.path.join(mesh, name), "wb") as out:
            out.write(header("labelList", name, binary).encode())
            write_list(out, values, binary, lambda v: "%d\n" % v)
    with open(os.path.join(mesh, "boundary"), "w") as out:
        out.write(header("polyBoundaryMesh", "boundary", False))
        out.write(f"1\n(\n    walls\n    {{\n        type            wall;\n        nFaces          {6 * n * n};\n"
                  f"        startFace       {len(neighbour)};\n    }}\n)\n")


def main():
    """Command line: CASE N [--ascii]."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("case")
    parser.add_argument("cells", type=int, help="cells per side")
    parser.add_argument("--ascii", action="store_true", help="ASCII lists (default: binary)")
    args = parser.parse_args()
    write_case(args.case, args.cells, not args.ascii)


if __name__ == "__main__":
    main()
