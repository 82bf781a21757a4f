"""Shared set-up of the add-on's tests, run inside Blender:
    blender -b --factory-startup --python-exit-code 1 --python tests/blender/test_X.py
CTest sets FFDKIT_ADDON_DIR (the source folder holding ffdkit_blender), FFDKIT_PYTHONPATH (the
build tree's python folder), FFDKIT_CLI (ffdkit-cli) and FFDKIT_SOURCE_DIR (the repository)."""

import atexit
import os
import shutil
import subprocess
import sys
import tempfile

import addon_utils
import bpy
import numpy as np


def env(name):
    value = os.environ.get(name)
    if not value:
        sys.exit("%s is not set: run this test through ctest (tests/blender/CMakeLists.txt)" % name)
    return value


SOURCE_DIR = env("FFDKIT_SOURCE_DIR")
CLI = env("FFDKIT_CLI")


def enable_addon():
    """Enables the add-on from the source tree in this factory-startup Blender; returns its module."""
    folder = env("FFDKIT_ADDON_DIR")
    if folder not in sys.path:
        sys.path.insert(0, folder)
    module = addon_utils.enable("ffdkit_blender", default_set=True, handle_error=lambda error: sys.exit(
        "enabling the add-on failed: %r" % error))
    assert module is not None, "addon_utils.enable returned None"
    assert hasattr(bpy.ops.ffdkit, "load_tool"), "the add-on registered no ffdkit.load_tool operator"
    module.ffdkit_module()  # finds the ffdkit package (FFDKIT_PYTHONPATH) and puts it on sys.path
    return module


def empty_scene():
    """Removes every object and mesh (read_factory_settings would disable the add-on)."""
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    for collection in (bpy.data.meshes, bpy.data.lattices, bpy.data.actions):
        for block in list(collection):
            collection.remove(block)
    bpy.context.scene.frame_set(1)


def add_mesh(name, points, faces=()):
    """A mesh object from #points x 3 vertices (stored as float32 by Blender), made active."""
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([tuple(p) for p in points], [], list(faces))
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    return obj


def sphere_points(count=400, centre=(0.3, -0.2, 0.1), radii=(0.8, 0.6, 0.5), seed=3):
    """Points on and inside an off-centre ellipsoid: a mesh with no symmetry the tools share."""
    rng = np.random.default_rng(seed)
    directions = rng.normal(size=(count, 3))
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    radius = rng.uniform(0.3, 1.0, size=(count, 1))
    return np.asarray(centre) + directions * radius * np.asarray(radii)


def vertices(obj):
    flat = np.empty(3 * len(obj.data.vertices), dtype=np.float32)
    obj.data.vertices.foreach_get("co", flat)
    return flat.reshape(-1, 3).astype(np.float64)


def shape_key_points(obj, name="ffdkit"):
    block = obj.data.shape_keys.key_blocks[name]
    flat = np.empty(3 * len(block.data), dtype=np.float32)
    block.data.foreach_get("co", flat)
    return flat.reshape(-1, 3).astype(np.float64)


def evaluated_points(obj):
    depsgraph = bpy.context.evaluated_depsgraph_get()
    mesh = obj.evaluated_get(depsgraph).data
    flat = np.empty(3 * len(mesh.vertices), dtype=np.float32)
    mesh.vertices.foreach_get("co", flat)
    return flat.reshape(-1, 3).astype(np.float64)


def run_cli(*args):
    result = subprocess.run([CLI, *args], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("ffdkit-cli %s failed (%d): %s" % (" ".join(args), result.returncode, result.stderr))
    return result.stdout


def temporary_folder():
    """A new folder, removed when Blender exits normally."""
    folder = tempfile.mkdtemp(prefix="ffdkit-blender-test-")
    atexit.register(shutil.rmtree, folder, True)
    return folder
