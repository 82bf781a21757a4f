"""ffdkit: direct-manipulation free-form deformation with 3D widgets, from Python.

Submodules mirror the C++ namespaces (docs/python.md):

- ``ffdkit.ffd``      lattices, embedding, deformation, pipelines, direct manipulation
- ``ffdkit.widgets``  the headless widget model (lattice, cell and affine widgets, bindings)
- ``ffdkit.scenes``   scenes (objects, lattices, keyframes), scene and widget files, the scene
                      deformer, mesh files, generators
- ``ffdkit.app``      a scene edited as the app edits it, one undoable command per operation
- ``ffdkit.io``       volume meshes (OpenFOAM, Gmsh, SU2, UNV, Elmer, LS-DYNA, Kratos) read to points
                      and written back by pass-through, and PyGeM's file handler classes
- ``ffdkit.cad``      STEP and IGES parts and their exact FFD (builds with OpenCASCADE; ``import ffdkit.cad``)
- ``ffdkit.pygem``    PyGeM's ``FFD``, ``CFFD``, ``BFFD`` and ``VFFD`` classes on ffdkit's engine

Points are numpy float64 arrays of shape (N, 3). Errors are ``ffdkit.Error`` subclasses carrying
the C++ messages.
"""

import sys as _sys

from ._ffdkit import (AnimationError, Cancelled, ConstraintError, Error, GeneratorError, LatticeError, MeshIoError,
                      SceneFileError, WidgetError, WidgetFileError, __version__, app, ffd, scenes,
                      widgets)

# `import ffdkit.ffd` and `from ffdkit.ffd import X` find the extension's submodules.
for _module in (ffd, widgets, scenes, app):
    _sys.modules[__name__ + "." + _module.__name__.rsplit(".", 1)[-1]] = _module

from . import io  # noqa: E402  (after the extension's submodules)

__all__ = ["ffd", "widgets", "scenes", "app", "io", "Error", "LatticeError", "ConstraintError", "Cancelled", "WidgetError",
           "WidgetFileError", "SceneFileError", "MeshIoError", "GeneratorError", "AnimationError",
           "__version__"]
