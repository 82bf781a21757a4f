"""Writing a mesh's worth of points into a shape key at the speed of a memory copy.

``ShapeKey.data.foreach_set("co", ...)`` is slow in Blender 3.4: a shape key point's ``co`` has
getter and setter functions in RNA (``rna_ShapeKeyPoint_co_set`` in ``rna_key.c``), so
``foreach_set`` cannot copy the array in one go and calls the setter once per point (about 110 ms
for 10^6 points, against 4 ms for ``MeshVertex.co``, which RNA maps straight onto ``MVert.co``).
A mesh key block's points are one array of ``float[3]`` (``KeyBlock.data``, ``Key.elemsize`` 12
bytes), and the RNA pointer of a point is the address of its three floats (``as_pointer``). When
the addresses of the first, second and last point say so, the points are converted from float64
straight into that array (one numpy pass, about 3 ms for 10^6 points); otherwise
``foreach_set`` writes them as before.

No Blender import here: the block is any object with Blender's ``ShapeKey`` interface.
"""

import ctypes

import numpy as np

_POINT_BYTES = 3 * ctypes.sizeof(ctypes.c_float)

DIRECT = "direct"
FOREACH_SET = "foreach_set"


def point_array(block, count):
    """The block's points as a writable count x 3 float32 numpy view of Blender's own array, or
    None when they are not laid out as one array of count float[3] (or count is 0). The view is
    valid until the key block is changed or freed: use it at once, never keep it."""
    data = block.data
    if count == 0 or len(data) != count:
        return None
    first = data[0].as_pointer()
    if first == 0:
        return None
    if count > 1 and (data[1].as_pointer() != first + _POINT_BYTES
                      or data[count - 1].as_pointer() != first + _POINT_BYTES * (count - 1)):
        return None
    array = np.frombuffer((ctypes.c_float * (3 * count)).from_address(first), dtype=np.float32).reshape(count, 3)
    if not np.array_equal(array[0], np.asarray(data[0].co, dtype=np.float32)):
        return None  # the address is not the point's coordinates after all
    return array


def write_points(block, points, allow_direct=True):
    """Writes #points x 3 coordinates into the shape key block's points.

    Args:
        block: a Blender ShapeKey of a mesh (bpy.types.ShapeKey).
        points: #points x 3 array (any float dtype), one row per vertex, the key's length.
        allow_direct: False forces foreach_set (the tests compare both).
    Returns:
        DIRECT when the points were copied into Blender's array, FOREACH_SET otherwise.
    Raises:
        ValueError: points is not #points x 3, or its length is not the key's.
    """
    points = np.asarray(points)
    if points.ndim != 2 or points.shape[1] != 3:
        raise ValueError("expected #points x 3 coordinates, got an array of shape %s" % (points.shape,))
    if points.shape[0] != len(block.data):
        raise ValueError("%d points for a shape key of %d" % (points.shape[0], len(block.data)))
    target = point_array(block, points.shape[0]) if allow_direct else None
    if target is not None:
        np.copyto(target, points, casting="same_kind")
        return DIRECT
    block.data.foreach_set("co", np.ascontiguousarray(points, dtype=np.float32).reshape(-1))
    return FOREACH_SET
