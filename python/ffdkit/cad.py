"""STEP and IGES parts, and their exact free-form deformation (docs/cad.md).

``read_step`` / ``read_iges`` read a part (or an assembly's parts) through OpenCASCADE, in a child
process with a time and a memory limit; ``deform`` composes a Bernstein lattice's FFD exactly
with every surface and curve of the B-rep (``method='exact'``), or moves each NURBS pole
(``method='poles'``, PyGeM's method, for comparison); ``write_step`` / ``write_iges`` write the
result; ``tessellate`` gives triangles and ``check`` OpenCASCADE's validity check and volume::

    import ffdkit.cad
    part = ffdkit.cad.read_step("part.step")
    deformed, report = ffdkit.cad.deform(part, lattice)   # lattice: an ffdkit.ffd.Lattice
    ffdkit.cad.write_step(deformed, "deformed.step")

Available when ffdkit was built with OpenCASCADE (FFDKIT_WITH_CAD); otherwise importing this
module raises ImportError saying so. Errors are ``ffdkit.cad.CadError`` (an ``ffdkit.Error`` and a
``RuntimeError``) naming the file, or the part and face.
"""

import os as _os

from . import _ffdkit

if not hasattr(_ffdkit, "_cad"):
    raise ImportError("ffdkit.cad: this ffdkit was built without OpenCASCADE (FFDKIT_WITH_CAD=OFF), which STEP and "
                      "IGES need")

_cad = _ffdkit._cad
CadError = _cad.CadError
Model = _cad.Model

__all__ = ["CadError", "Model", "read_step", "read_iges", "write_step", "write_iges", "deform", "tessellate", "check",
           "enclosed_volume", "make_sample_part"]


def read_step(path, max_seconds=None, isolate=True):
    """Reads a STEP file (AP203, AP214, AP242 geometry) into a Model.

    Every free shape of the file becomes a part; an assembly's parts are flattened, each placed
    by its instances' placements and named after its product. Lengths in millimetres.

    Args:
        path: the file (str or os.PathLike).
        max_seconds: the reading stops with CadError after this many seconds (None: 120; 0: no limit).
        isolate: read in a child process, so that a file that crashes OpenCASCADE is a CadError.

    Returns:
        Model: the parts read.

    Raises:
        CadError: naming the file: missing, too large, not STEP, a transfer OpenCASCADE fails on or
            that runs out of time or memory, no shape in the file.
    """
    return _cad.read_step(_os.fspath(path), max_seconds, isolate)


def read_iges(path, max_seconds=None, isolate=True):
    """Reads an IGES file (trimmed surfaces, shells, MSBO solids) into a Model.

    Args:
        path: the file (str or os.PathLike).
        max_seconds: the reading stops with CadError after this many seconds (None: 120; 0: no limit).
        isolate: read in a child process, so that a file that crashes OpenCASCADE is a CadError.

    Returns:
        Model: the parts read, named from the entities' labels.

    Raises:
        CadError: naming the file, as read_step.
    """
    return _cad.read_iges(_os.fspath(path), max_seconds, isolate)


def write_step(model, path):
    """Writes a Model as STEP AP214, one product per part.

    The file is written beside ``path`` and renamed onto it when complete: a failure leaves
    ``path`` as it was.

    Args:
        model: the Model to write.
        path: the output file (str or os.PathLike).

    Returns:
        None.

    Raises:
        CadError: naming the file when OpenCASCADE cannot transfer or write it.
    """
    _cad.write_step(model, _os.fspath(path))


def write_iges(model, path):
    """Writes a Model as IGES 5.3 in BRep mode (solids as MSBO entities), atomically as write_step.

    Args:
        model: the Model to write.
        path: the output file (str or os.PathLike).

    Returns:
        None.

    Raises:
        CadError: naming the file when OpenCASCADE cannot transfer or write it.
    """
    _cad.write_iges(model, _os.fspath(path))


def deform(model, lattice, method="exact", max_degree=15, samples=0):
    """Deforms every part of a Model by a lattice's FFD, keeping its topology.

    Every vertex, edge and face goes through the same map, so faces that shared an edge still
    share it. ``'exact'`` composes the lattice's polynomial with every surface and curve (the
    written surfaces are the FFD of the original ones, to rounding); it needs a Bernstein lattice
    with a box rest shape and the parts inside it (or the Extrapolate outside policy).
    ``'poles'`` moves each NURBS pole by the FFD (PyGeM's method: not the FFD of the surface,
    and gaps between faces).

    Args:
        model: the Model to deform.
        lattice: an ffdkit.ffd.Lattice, in world coordinates.
        method: 'exact' or 'poles'.
        max_degree: 'exact': the highest degree per direction a composed surface may reach (1..25).
        samples: > 0: measure the result on samples x samples points per face and samples points
            per edge (report's max_deviation and max_gap); 0: skip.

    Returns:
        tuple: (Model, dict) the deformed model and a report with faces, edges, max_degree,
        max_deviation, max_gap and seconds.

    Raises:
        CadError: naming the part and face when the lattice or a part does not meet the exact
            method's conditions, a degree exceeds max_degree, or OpenCASCADE fails.
        ValueError: for a method other than 'exact' or 'poles'.
    """
    return _cad.deform(model, lattice, method, max_degree, samples)


def tessellate(model, linear_deflection=0.0, angular_deflection=0.5, max_edge_length=0.0):
    """Triangles of every face of every part (OpenCASCADE's BRepMesh).

    Each face has its own points (a face's boundary points are not merged with its neighbour's);
    triangles are oriented outwards for solids.

    Args:
        model: the Model to tessellate.
        linear_deflection: the largest distance between a triangle and its face, in model units
            (0: 1e-3 x the model's bounding-box diagonal).
        angular_deflection: the largest angle between a triangle's normals and the face's, radians.
        max_edge_length: > 0: the longest edges are bisected (in every triangle that has them) until
            none is longer, so that a plane, which BRepMesh gives its boundary's points only, has
            inner points a deformation can move (0: no limit).

    Returns:
        tuple: (points, triangles, part_of_triangle): float64 (N, 3), int (T, 3) and int (T,) arrays.

    Raises:
        CadError: if a deflection is not > 0 and finite, max_edge_length is negative or would make
            more than 20 million triangles, or meshing fails.
    """
    return _cad.tessellate(model, linear_deflection, angular_deflection, max_edge_length)


def check(model):
    """Checks every part with OpenCASCADE's BRepCheck_Analyzer and measures its volume (BRepGProp).

    Args:
        model: the Model to check.

    Returns:
        dict: valid (bool), first_problem (str, empty when valid), volume (float, the parts'
        solids) and max_tolerance (the largest vertex, edge or face tolerance).

    Raises:
        CadError: if OpenCASCADE throws while checking.
    """
    return _cad.check(model)


def enclosed_volume(points, triangles):
    """The volume a closed, outward-oriented triangle set encloses (divergence theorem).

    Args:
        points: float (N, 3) array.
        triangles: int (T, 3) array of indices into points.

    Returns:
        float: the enclosed volume.

    Raises:
        ValueError: for arrays of the wrong shape.
    """
    return _cad.enclosed_volume(points, triangles)


def make_sample_part(name):
    """A part built with OpenCASCADE's modelling API, for tests and examples.

    Args:
        name: 'filleted-box', 'blade', 'bent-pipe', 'bottle' or 'two-part-assembly'.

    Returns:
        Model: the part.

    Raises:
        ValueError: for an unknown name.
        CadError: if OpenCASCADE fails to build it.
    """
    return _cad.make_sample_part(name)
