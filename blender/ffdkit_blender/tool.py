"""A widget tool (an ffdkit widget file) deforming the points of one mesh.

No Blender types here: the add-on's operators and handlers hand this module numpy arrays, and the
tests can drive it without Blender. The tool is an ffdkit scene with one object (the mesh's rest
points, in the mesh's own coordinates) and every root lattice of the widget file attached to it,
evaluated by ffdkit's SceneDeformer exactly as ``ffdkit-cli deform --widgets`` evaluates it.
"""

import json
import os
import shutil
import tempfile

import numpy as np

OBJECT_NAME = "mesh"
# Margin of a fitted tool, relative to the mesh's bounding-box diagonal: the default of the app's
# Attach and of ffdkit-cli deform --fit --padding.
FIT_PADDING = 0.05


class ToolError(ValueError):
    """Input the tool cannot use; the message is for the user and names what and where."""


def read_widget_text(ffdkit, path):
    """Reads and checks a widget file; returns its canonical text (scenes.widgetFileText).

    Raises:
        ToolError: the file is missing, unreadable or not a valid widget file (ffdkit's message,
            which names the file and the place in it).
    """
    if not os.path.isfile(path):
        raise ToolError("%s: no such widget file" % path)
    try:
        model = ffdkit.scenes.readWidgetFile(path)
    except (ffdkit.Error, OSError, ValueError) as error:
        raise ToolError(str(error)) from None
    if not model.roots():
        raise ToolError("%s: the widget file has no lattice, so it deforms nothing" % path)
    return ffdkit.scenes.widgetFileText(model)


def _fit_roots(scene, points, padding):
    """Places the tool around the points as ``ffdkit-cli deform --fit`` does: one scale-and-
    translate map takes the box of the root lattices' rest shapes onto the points' box grown by
    ``padding`` x its diagonal (scenes/lattice_fit.h), and every root frame F becomes map @ F, so
    a tool of several root lattices keeps its layout."""
    model = scene.widgets
    roots = model.roots()
    rest = np.vstack([model.worldRestPoints(root) for root in roots])
    tool_lo, tool_hi = rest.min(axis=0), rest.max(axis=0)
    lo, hi = points.min(axis=0), points.max(axis=0)
    # The fitted box by the library's own rule: a probe lattice fitted to the object, then removed.
    probe = scene.attachNewLattice([OBJECT_NAME], name="ffdkit-blender-fit-probe", counts=(2, 2, 2), padding=padding)
    fitted = np.array(scene.widgets.latticeFrame(probe))
    scene.detachLattice(probe, OBJECT_NAME)
    scene.widgets.remove(probe)
    size = np.diag(fitted)[:3]
    tool_size = np.maximum(tool_hi - tool_lo, 1e-12 * max(1.0, float(np.linalg.norm(tool_hi - tool_lo))))
    scale = size / tool_size
    fit = np.eye(4)
    fit[:3, :3] = np.diag(scale)
    fit[:3, 3] = 0.5 * (lo + hi) - scale * (0.5 * (tool_lo + tool_hi))
    model = scene.widgets
    for root in model.roots():
        model.setLatticeFrame(root, fit @ np.array(model.latticeFrame(root)))


class Tool:
    """One widget tool on one mesh: its variations in, the deformed points out.

    Args:
        ffdkit: the ffdkit package (runtime.load()).
        widget_text: a widget file's text (read_widget_text).
        rest_points: #points x 3, the mesh's undeformed points in its own coordinates.
        fit: place the tool around the points (_fit_roots); False keeps the lattices' stored frames.
        mesh_name: the mesh's name, for messages.
        roots: names of the root lattices that deform the mesh (None: every root lattice).
    Raises:
        ToolError: no points, non-finite points, or (not fitted) no point inside any root lattice.
    """

    def __init__(self, ffdkit, widget_text, rest_points, fit=True, mesh_name="mesh", roots=None):
        self._ffdkit = ffdkit
        points = np.asarray(rest_points, dtype=np.float64).reshape(-1, 3)
        if points.shape[0] == 0:
            raise ToolError("'%s' has no vertices: there is nothing to deform" % mesh_name)
        if not np.isfinite(points).all():
            raise ToolError("'%s' has vertices that are not finite numbers" % mesh_name)
        self.rest_points = points
        self.scene = self._build_scene(widget_text, points, roots)
        if fit:
            _fit_roots(self.scene, points, FIT_PADDING)
        else:
            self._check_reach(points, mesh_name)
        model = self.scene.widgets
        affine = ffdkit.widgets.WidgetType.Affine
        self._affines = {model.name(w): w for w in model.widgets(affine)}
        self.deformer = ffdkit.scenes.SceneDeformer()
        self._applied = self.variations()

    def _build_scene(self, widget_text, points, chosen):
        folder = tempfile.mkdtemp(prefix="ffdkit-blender-")
        try:
            np.save(os.path.join(folder, "points.npy"), points)
            with open(os.path.join(folder, "tool.json"), "w", encoding="utf-8") as out:
                out.write(widget_text)
            try:
                model = self._ffdkit.scenes.readWidgetFile(os.path.join(folder, "tool.json"))
            except (self._ffdkit.Error, OSError, ValueError) as error:
                raise ToolError(str(error).replace(folder + os.sep, "")) from None
            roots = [model.name(root) for root in model.roots()]
            if chosen is not None:
                unknown = sorted(set(chosen) - set(roots))
                if unknown:
                    raise ToolError("the tool has no root lattice %s (its roots: %s)" % (", ".join(unknown), ", ".join(roots)))
                roots = [name for name in roots if name in chosen]
            scene = {
                "format": "ffdkit-scene",
                "version": 2,
                "objects": [{"name": OBJECT_NAME, "mesh": {"path": "points.npy"}}],
                "widgetFile": "tool.json",
                "attachments": [{"lattice": name, "objects": [OBJECT_NAME]} for name in roots],
            }
            with open(os.path.join(folder, "scene.json"), "w", encoding="utf-8") as out:
                json.dump(scene, out)
            try:
                return self._ffdkit.scenes.readScene(folder)
            except (self._ffdkit.Error, OSError, ValueError) as error:
                raise ToolError(str(error).replace(folder + os.sep, "")) from None
        finally:
            shutil.rmtree(folder, ignore_errors=True)

    def _check_reach(self, points, mesh_name):
        model = self.scene.widgets
        for root in model.roots():
            rest = np.asarray(model.worldRestPoints(root))
            lo, hi = rest.min(axis=0), rest.max(axis=0)
            if np.any(np.all((points >= lo) & (points <= hi), axis=1)):
                return
        raise ToolError("the tool's lattices, at their stored places, reach none of the %d vertices of '%s': "
                        "load it fitted to the mesh, or move the mesh into the lattices"
                        % (points.shape[0], mesh_name))

    def affine_names(self):
        """Names of the affine widgets, in the model's order (one slider each)."""
        return list(self._affines)

    def affine_kind(self, name):
        """'TRANSLATE', 'ROTATE' or 'SCALE'."""
        return self.scene.widgets.affineKind(self._affines[name]).name.upper()

    def variations(self):
        """{name: variation} of every affine widget (world distance, radians or log scale)."""
        model = self.scene.widgets
        return {name: model.variation(w) for name, w in self._affines.items()}

    def set_variations(self, values):
        """Applies the values that changed since the last call, in the given order, with
        WidgetModel.setVariation: bound widgets follow as in ffdkit. A value equal to what the
        tool last reported is not applied, so a follower's slider (written back by the caller)
        does not undo its leader's change.

        Args:
            values: {affine name: variation}; unknown names are ignored.
        Returns:
            True when some variation changed.
        """
        model = self.scene.widgets
        changed = False
        for name, value in values.items():
            widget = self._affines.get(name)
            if widget is None or value == self._applied.get(name):
                continue
            model.setVariation(widget, float(value))
            changed = True
        self._applied = self.variations()
        return changed

    def points(self):
        """The deformed points, #points x 3 float64 (a view the next call rewrites)."""
        self.deformer.update(self.scene)
        return self.deformer.points(OBJECT_NAME)

