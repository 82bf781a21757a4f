"""The link between a tool and a Blender mesh object: the stored tool, the variation properties,
the shape key the deformation is written into, and the handlers that keep it current.

What is stored on the object (saved in the .blend):
- ``_ffdkit_tool``: the widget file's canonical text; ``_ffdkit_source``: the file it came from;
  ``_ffdkit_fit``: whether the tool was fitted around the mesh (else at its stored frames).
- ``ffd:<widget>``: one float per affine widget, its variation (world distance, radians or log
  scale): a slider in the ffdkit panel, keyable (I over the slider) and drivable.
- The shape key ``ffdkit`` (value 1, relative to the mesh's reference key): the deformed points.
  The rest points are the reference key's (``Basis``), so other shape keys still add on top.
The Tool objects (with ffdkit's embedding) live only in memory and are rebuilt from the stored
text when a file is opened.
"""

import json

import numpy as np

from . import key_write
from . import tool as tool_module

PREFIX = "ffd:"
TOOL_KEY = "_ffdkit_tool"
SOURCE_KEY = "_ffdkit_source"
FIT_KEY = "_ffdkit_fit"
ROOTS_KEY = "_ffdkit_roots"  # JSON list of the root lattices deforming the mesh (absent: all)
STATE_KEY = "_ffdkit_state"  # the tool's widget file as placed and posed when the .blend was saved
SHAPE_KEY = "ffdkit"

# Object name -> _Link. Rebuilt on demand (after a file is opened, or an undo that changed the text).
_links = {}


class _Link:
    def __init__(self, tool, text):
        self.tool = tool
        self.text = text
        self.dirty = True  # the shape key must be (re)written
        self.error = ""
        self.write_path = ""  # how the last write went: key_write.DIRECT or FOREACH_SET


def has_tool(obj):
    return obj is not None and obj.type == "MESH" and TOOL_KEY in obj.keys()


def rest_points(mesh):
    """The mesh's undeformed points, #vertices x 3 float64: its reference shape key's, else its vertices'."""
    count = len(mesh.vertices)
    flat = np.empty(3 * count, dtype=np.float32)
    if mesh.shape_keys is not None and mesh.shape_keys.reference_key is not None:
        mesh.shape_keys.reference_key.data.foreach_get("co", flat)
    else:
        mesh.vertices.foreach_get("co", flat)
    return flat.reshape(-1, 3).astype(np.float64)


def _roots(obj):
    return json.loads(obj[ROOTS_KEY]) if ROOTS_KEY in obj.keys() else None


def attach(ffdkit, obj, text, source, fit, roots=None):
    """Builds the tool on the object and stores it; the mesh changes only when this succeeds.
    `roots`: the root lattices deforming the mesh (None: all).

    Raises:
        tool.ToolError: the mesh or the tool cannot be used (nothing on the object is changed).
    """
    tool = tool_module.Tool(ffdkit, text, rest_points(obj.data), fit=fit, mesh_name=obj.name, roots=roots)
    detach(obj)
    obj[TOOL_KEY] = text
    if roots is not None:
        obj[ROOTS_KEY] = json.dumps(list(roots))
    obj[SOURCE_KEY] = source
    obj[FIT_KEY] = bool(fit)
    for name, value in tool.variations().items():
        key = PREFIX + name
        obj[key] = float(value)
        _describe_property(obj, key, tool.affine_kind(name))
    if obj.data.shape_keys is None:
        obj.shape_key_add(name="Basis", from_mix=False)
    block = obj.shape_key_add(name=SHAPE_KEY, from_mix=False)
    block.value = 1.0
    block.relative_key = obj.data.shape_keys.reference_key
    link = _Link(tool, text)
    _links[obj.name] = link
    write(obj, link)
    return tool


def detach(obj):
    """Removes the tool, its properties (and their animation curves) and its shape key."""
    _links.pop(obj.name, None)
    for key in [k for k in obj.keys() if k.startswith(PREFIX) or k in (TOOL_KEY, SOURCE_KEY, FIT_KEY, ROOTS_KEY, STATE_KEY)]:
        if obj.animation_data and obj.animation_data.action:
            curve = obj.animation_data.action.fcurves.find('["%s"]' % key)
            if curve is not None:
                obj.animation_data.action.fcurves.remove(curve)
        del obj[key]
    keys = obj.data.shape_keys
    if keys is not None and SHAPE_KEY in keys.key_blocks:
        obj.shape_key_remove(keys.key_blocks[SHAPE_KEY])
        keys = obj.data.shape_keys
        if keys is not None and len(keys.key_blocks) == 1:
            obj.shape_key_remove(keys.key_blocks[0])  # only the Basis this add-on made is left


def _describe_property(obj, key, kind):
    subtype = {"TRANSLATE": "DISTANCE", "ROTATE": "ANGLE"}.get(kind, "NONE")
    span = {"TRANSLATE": 1.0, "ROTATE": 3.141592653589793, "SCALE": 1.0}.get(kind, 1.0)
    what = {"TRANSLATE": "world distance", "ROTATE": "radians", "SCALE": "log scale"}.get(kind, "")
    obj.id_properties_ui(key).update(subtype=subtype, soft_min=-span, soft_max=span, default=0.0,
                                     description="ffdkit %s widget '%s': its variation (%s)"
                                     % (kind.lower(), key[len(PREFIX):], what))


def link_of(ffdkit, obj):
    """The object's live link, rebuilt from the stored tool when missing or stale; None on error."""
    text = obj.get(TOOL_KEY)
    link = _links.get(obj.name)
    if link is not None and link.text == text:
        return link
    link = _Link(None, text)
    try:
        if STATE_KEY in obj.keys():
            # As saved: placed, and posed as the sliders were (applying the sliders one by one to
            # the file's rest pose would move bound followers twice).
            link.tool = tool_module.Tool(ffdkit, obj[STATE_KEY], rest_points(obj.data), fit=False,
                                         mesh_name=obj.name, roots=_roots(obj))
        else:
            link.tool = tool_module.Tool(ffdkit, text, rest_points(obj.data), fit=bool(obj.get(FIT_KEY, True)),
                                         mesh_name=obj.name, roots=_roots(obj))
    except tool_module.ToolError as error:
        link.error = str(error)
    _links[obj.name] = link
    return link


def link_error(obj):
    """Why the object's stored tool could not be rebuilt ("" when it was, or was not tried yet)."""
    link = _links.get(obj.name)
    return link.error if link is not None else ""


def _curve(obj, key):
    """The action's F-curve animating the property, or None."""
    data = obj.animation_data
    if data is None or data.action is None:
        return None
    return data.action.fcurves.find('["%s"]' % key)


def _driven(obj, key):
    data = obj.animation_data
    return data is not None and any(driver.data_path == '["%s"]' % key for driver in data.drivers)


def _values(obj, names, evaluated, frame):
    """{name: variation} the tool should have: the evaluated object's values when given (keys and
    drivers applied by Blender); else the object's own values, keyed ones evaluated at `frame`
    from their F-curves when a frame is given (a new frame, before Blender evaluates it: the own
    value still holds the last frame's; without a frame the own value is current, and may be an
    edit the keys do not hold yet). Driven ones are left to the evaluated pass."""
    values = {}
    for name in names:
        key = PREFIX + name
        if evaluated is not None:
            if key in evaluated.keys():
                values[name] = float(evaluated[key])
            continue
        if key not in obj.keys() or _driven(obj, key):
            continue
        curve = _curve(obj, key) if frame is not None else None
        values[name] = float(curve.evaluate(frame)) if curve is not None else float(obj[key])
    return values


def sync(ffdkit, obj, evaluated=None, frame=None):
    """Applies the object's variation properties to its tool and writes the shape key when
    something changed; followers of a binding get their properties written back unless they are
    animated. Run before Blender evaluates (the object's own values; with `frame`, a new frame's
    keyed values), the write joins that evaluation; run after it (evaluated given), driven values
    are caught too and the write asks for one more evaluation."""
    link = link_of(ffdkit, obj)
    if link.tool is None:
        return False
    changed = link.tool.set_variations(_values(obj, link.tool.affine_names(), evaluated, frame))
    if not (changed or link.dirty):
        return False
    for name, value in link.tool.variations().items():
        key = PREFIX + name
        if key in obj.keys() and float(obj[key]) != value and _curve(obj, key) is None and not _driven(obj, key):
            obj[key] = value
    write(obj, link)
    return True


def write(obj, link):
    """Writes the tool's deformed points into the object's ffdkit shape key (key_write: a copy
    into Blender's array, else one foreach_set) and tags the shape keys for evaluation. Only the
    Key data-block is tagged, not the mesh: a tagged mesh is copied whole for evaluation (its
    vertices, edges, faces and corners), which costs more than the rest of a slider change; the
    Key's tag alone re-evaluates the mesh's geometry and the object's modifier stack."""
    keys = obj.data.shape_keys
    if keys is None or SHAPE_KEY not in keys.key_blocks:
        return
    link.write_path = key_write.write_points(keys.key_blocks[SHAPE_KEY], link.tool.points())
    keys.update_tag()
    link.dirty = False


def store_states(ffdkit, objects):
    """Before a save: each tool's present widget file (placed and posed) goes into the object."""
    for obj in objects:
        link = _links.get(obj.name)
        if has_tool(obj) and link is not None and link.tool is not None and link.text == obj.get(TOOL_KEY):
            obj[STATE_KEY] = ffdkit.scenes.widgetFileText(link.tool.scene.widgets)


def forget_all(mark_dirty_only=False):
    """After an undo or a file load: links are rebuilt (or rewritten) on the next sync."""
    if mark_dirty_only:
        for link in _links.values():
            link.dirty = True
    else:
        _links.clear()


def bake(scene, obj, frames):
    """Writes the deformation at each frame into a shape key 'ffdkit <frame>' whose value is keyed
    1 at its frame and 0 at the neighbouring baked frames (linear), and mutes the live key: the
    animation then plays back from the shape keys alone. Returns the number of frames baked."""
    keys = obj.data.shape_keys
    live = keys.key_blocks[SHAPE_KEY]
    live.mute = False
    current = scene.frame_current
    flat = np.empty(3 * len(live.data), dtype=np.float32)
    blocks = []
    for frame in frames:
        scene.frame_set(frame)  # frame_change_post writes the live key
        live.data.foreach_get("co", flat)
        name = "%s %d" % (SHAPE_KEY, frame)
        if name in keys.key_blocks:
            obj.shape_key_remove(keys.key_blocks[name])
        block = obj.shape_key_add(name=name, from_mix=False)
        block.relative_key = keys.reference_key
        block.data.foreach_set("co", flat)
        blocks.append((frame, block))
    for index, (frame, block) in enumerate(blocks):
        path = 'key_blocks["%s"].value' % block.name
        neighbours = [blocks[j][0] for j in (index - 1, index + 1) if 0 <= j < len(blocks)]
        for at, value in [(frame, 1.0)] + [(n, 0.0) for n in neighbours]:
            block.value = value
            keys.keyframe_insert(path, frame=at)
        curve = keys.animation_data.action.fcurves.find(path)
        for point in curve.keyframe_points:
            point.interpolation = "LINEAR"
    live.mute = True
    scene.frame_set(current)
    return len(blocks)
