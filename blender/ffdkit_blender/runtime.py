"""Finds the ``ffdkit`` Python module for the add-on.

The module is looked for, in this order: on Blender's own ``sys.path`` (the Debian package puts it
in ``/usr/lib/python3/dist-packages``, which Debian's Blender reads); in the folder named by the
environment variable ``FFDKIT_PYTHONPATH`` (a build tree: ``build/python``); in the folder set in
the add-on's preferences; in ``<prefix>/lib/python3/dist-packages`` when the add-on was installed
by ``cmake --install`` under ``<prefix>/share/blender/scripts/addons``.
"""

import importlib
import os
import sys

_ADDON_DIR = os.path.dirname(os.path.abspath(__file__))


def candidate_folders(preference_path=""):
    """The folders tried after sys.path, in order (existing ones only)."""
    folders = []
    if os.environ.get("FFDKIT_PYTHONPATH"):
        folders.extend(os.environ["FFDKIT_PYTHONPATH"].split(os.pathsep))
    if preference_path:
        folders.append(preference_path)
    # <prefix>/share/blender/scripts/addons/ffdkit_blender -> <prefix>/lib/python3/dist-packages
    prefix = os.path.normpath(os.path.join(_ADDON_DIR, "..", "..", "..", "..", ".."))
    folders.append(os.path.join(prefix, "lib", "python3", "dist-packages"))
    return [f for f in folders if f and os.path.isdir(os.path.join(f, "ffdkit"))]


class ModuleNotFound(ImportError):
    """The ffdkit module is nowhere the add-on looks; the message says where it looked."""


def load(preference_path=""):
    """Imports and returns the ffdkit package (with its ffd, widgets and scenes modules).

    Raises:
        ModuleNotFound: the module is not installed where the add-on looks, or does not load
            (built for another Python: Blender runs Python %d.%d).
    """
    try:
        return importlib.import_module("ffdkit")
    except ImportError as first:
        tried = candidate_folders(preference_path)
        for folder in tried:
            if folder not in sys.path:
                sys.path.append(folder)
            try:
                return importlib.import_module("ffdkit")
            except ImportError as error:
                first = error
        raise ModuleNotFound(
            "the ffdkit Python module was not found or did not load (%s); looked on sys.path and in %s. "
            "Install ffdkit (its .deb or cmake --install), set FFDKIT_PYTHONPATH to build/python, or set "
            "the module folder in the add-on's preferences. Blender runs Python %d.%d."
            % (first, ", ".join(tried) or "no other folder", sys.version_info[0], sys.version_info[1])) from first
