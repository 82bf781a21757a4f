"""The add-on's write into the shape key: the direct copy into Blender's point array (key_write)
gives the same key as foreach_set, bit for bit; a slider change picked up by the add-on's poll
(nothing else tagged) reaches the evaluated mesh through a modifier after the key, as
ffdkit-cli deform gives it; bad arrays are refused."""

import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blender_support as support  # noqa: E402

addon = support.enable_addon()
import ffdkit  # noqa: E402  (found by the add-on)
from ffdkit_blender import key_write, mesh_link  # noqa: E402

TOLERANCE = 1e-6
folder = support.temporary_folder()
tool = os.path.join(support.SOURCE_DIR, "widgets", "examples", "fig6-8.json")
rest = support.sphere_points()

support.empty_scene()
obj = support.add_mesh("part", rest)
stored = support.vertices(obj)
assert bpy.ops.ffdkit.load_tool(filepath=tool, fit=True) == {"FINISHED"}
# A modifier after the key: Displace without a texture moves every point by
# (1 - mid level) x strength along X.
displace = obj.modifiers.new("after", "DISPLACE")
displace.direction = "X"
displace.mid_level = 0.5
displace.strength = 0.4
shift = np.array([0.2, 0.0, 0.0])
bpy.context.view_layer.update()

# A slider change as the interface makes it: the property changes and nothing is tagged; the
# add-on's poll applies it, writes the key and tags it; the next evaluation shows it.
obj["ffd:push-front"] = 0.15
addon._poll()
link = mesh_link.link_of(ffdkit, obj)
assert link.write_path == key_write.DIRECT, "the key was written by %r, not copied directly" % link.write_path
bpy.context.view_layer.update()

np.save(os.path.join(folder, "in.npy"), stored)
out = os.path.join(folder, "out.npy")
support.run_cli("deform", "-q", "-w", tool, os.path.join(folder, "in.npy"), "-o", out, "--fit",
                "--set", "push-front=0.15")
expected = np.load(out)
assert np.abs(expected - stored).max() > 1e-3, "the slider did not move the points"
keyed_error = np.abs(support.shape_key_points(obj) - expected).max()
evaluated_error = np.abs(support.evaluated_points(obj) - (expected + shift)).max()
print("poll -> key: max |key - cli| %.2e; evaluated through the modifier: %.2e" % (keyed_error, evaluated_error))
assert keyed_error <= TOLERANCE, keyed_error
assert evaluated_error <= TOLERANCE, evaluated_error
assert np.array_equal(support.vertices(obj), stored), "the mesh's own vertices were written"

# The direct copy and foreach_set store the same float32 bits (float64 rounded to nearest).
block = obj.data.shape_keys.key_blocks[mesh_link.SHAPE_KEY]
points = np.random.default_rng(7).normal(size=(len(rest), 3)) * 1e3
assert key_write.write_points(block, points, allow_direct=False) == key_write.FOREACH_SET
by_foreach = support.shape_key_points(obj)
assert key_write.write_points(block, points[::-1].copy()) == key_write.DIRECT  # something else first
assert key_write.write_points(block, points) == key_write.DIRECT
assert np.array_equal(support.shape_key_points(obj), by_foreach), "the direct copy differs from foreach_set"
assert np.array_equal(by_foreach, points.astype(np.float32).astype(np.float64))
# A strided (non-contiguous) array is copied as well.
assert key_write.write_points(block, np.asfortranarray(points)) == key_write.DIRECT
assert np.array_equal(support.shape_key_points(obj), by_foreach)

# Refused: a wrong shape or length, with the key left as it was.
for bad in (points[:-1], points[:, :2], points.reshape(-1)):
    try:
        key_write.write_points(block, bad)
    except ValueError as error:
        print("refused:", error)
    else:
        raise AssertionError("an array of shape %s was written" % (bad.shape,))
assert np.array_equal(support.shape_key_points(obj), by_foreach)
assert key_write.point_array(block, len(rest) + 1) is None
print("key_write: direct copy equals foreach_set")
