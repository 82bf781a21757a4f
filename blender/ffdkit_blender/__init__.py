"""ffdkit in Blender: widget tools (ffdkit widget files) deforming Blender meshes.

Object > ffdkit (or the ffdkit tab of the 3D view's sidebar): "Load Widget Tool" reads a widget
file onto the active mesh; each affine widget becomes a slider (a keyable, drivable custom
property ``ffd:<name>``); the deformation is written into the shape key ``ffdkit`` whenever a
variation changes. See docs/blender.md.
"""

bl_info = {
    "name": "ffdkit",
    "author": "ffdkit developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > ffdkit",
    "description": "Direct-manipulation free-form deformation: ffdkit widget tools on meshes",
    "category": "Object",
}

import bpy
import mathutils
from bpy.app.handlers import persistent
from bpy.props import BoolProperty, IntProperty, StringProperty

from . import lattice_convert, mesh_link, runtime, scene_io
from . import tool as tool_module


def ffdkit_module():
    """The ffdkit package (runtime.load with the preferences' folder); raises runtime.ModuleNotFound."""
    preferences = bpy.context.preferences.addons.get(__package__)
    folder = preferences.preferences.module_path if preferences is not None else ""
    return runtime.load(bpy.path.abspath(folder) if folder else "")


class FFDKIT_AP_preferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    module_path: StringProperty(
        name="ffdkit module folder", subtype="DIR_PATH",
        description="Folder holding the ffdkit Python package (e.g. build/python), when Blender does not find it")

    def draw(self, context):
        self.layout.prop(self, "module_path")
        try:
            module = ffdkit_module()
            self.layout.label(text="ffdkit %s: %s" % (module.__version__, module.__file__))
        except runtime.ModuleNotFound as error:
            self.layout.label(text=str(error), icon="ERROR")


class FFDKIT_OT_load_tool(bpy.types.Operator):
    """Load an ffdkit widget file onto the active mesh: one slider per affine widget"""

    bl_idname = "ffdkit.load_tool"
    bl_label = "Load Widget Tool"
    bl_options = {"REGISTER", "UNDO"}

    filepath: StringProperty(subtype="FILE_PATH")
    filter_glob: StringProperty(default="*.json", options={"HIDDEN"})
    fit: BoolProperty(name="Fit to Mesh", default=True,
                      description="Place the tool around the mesh (as ffdkit-cli deform --fit); "
                                  "off: at the frames stored in the file, in the mesh's own coordinates")

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def execute(self, context):
        obj = context.active_object
        if obj is None:
            self.report({"ERROR"}, "no active object: select a mesh to load the widget tool onto")
            return {"CANCELLED"}
        if obj.type != "MESH":
            self.report({"ERROR"}, "'%s' is a %s, not a mesh: the widget tool deforms meshes"
                        % (obj.name, obj.type.lower()))
            return {"CANCELLED"}
        if obj.mode != "OBJECT":
            self.report({"ERROR"}, "'%s' is in %s mode: load the widget tool in object mode"
                        % (obj.name, obj.mode.lower()))
            return {"CANCELLED"}
        try:
            ffdkit = ffdkit_module()
            text = tool_module.read_widget_text(ffdkit, bpy.path.abspath(self.filepath))
            tool = mesh_link.attach(ffdkit, obj, text, self.filepath, self.fit)
        except (runtime.ModuleNotFound, tool_module.ToolError) as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        self.report({"INFO"}, "'%s': %d widget sliders from %s"
                    % (obj.name, len(tool.affine_names()), bpy.path.basename(self.filepath)))
        return {"FINISHED"}


class FFDKIT_OT_remove_tool(bpy.types.Operator):
    """Remove the widget tool from the active mesh: its sliders, their keys and its shape key"""

    bl_idname = "ffdkit.remove_tool"
    bl_label = "Remove Widget Tool"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return mesh_link.has_tool(context.active_object)

    def execute(self, context):
        mesh_link.detach(context.active_object)
        return {"FINISHED"}


class FFDKIT_OT_bake_shape_keys(bpy.types.Operator):
    """Bake the widget tool's deformation, frame by frame, into shape keys that play back without the add-on"""

    bl_idname = "ffdkit.bake_shape_keys"
    bl_label = "Bake to Shape Keys"
    bl_options = {"REGISTER", "UNDO"}

    frame_start: IntProperty(name="Start", default=1)
    frame_end: IntProperty(name="End", default=250)
    frame_step: IntProperty(name="Step", default=1, min=1)

    @classmethod
    def poll(cls, context):
        return mesh_link.has_tool(context.active_object)

    def invoke(self, context, event):
        self.frame_start, self.frame_end = context.scene.frame_start, context.scene.frame_end
        return context.window_manager.invoke_props_dialog(self)

    def execute(self, context):
        if self.frame_end < self.frame_start:
            self.report({"ERROR"}, "the frame range %d..%d is empty" % (self.frame_start, self.frame_end))
            return {"CANCELLED"}
        try:
            ffdkit_module()
        except runtime.ModuleNotFound as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        frames = list(range(self.frame_start, self.frame_end + 1, self.frame_step))
        baked = mesh_link.bake(context.scene, context.active_object, frames)
        self.report({"INFO"}, "baked %d frames of '%s' into shape keys (the live key '%s' is muted)"
                    % (baked, context.active_object.name, mesh_link.SHAPE_KEY))
        return {"FINISHED"}


class FFDKIT_OT_import_scene(bpy.types.Operator):
    """Import an ffdkit scene: its objects as meshes with the scene's widget tool, sliders and keys"""

    bl_idname = "ffdkit.import_scene"
    bl_label = "Import ffdkit Scene"
    bl_options = {"REGISTER", "UNDO"}

    filepath: StringProperty(subtype="FILE_PATH")
    filter_glob: StringProperty(default="*.json", options={"HIDDEN"})

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def execute(self, context):
        path = bpy.path.abspath(self.filepath)
        try:
            ffdkit = ffdkit_module()
            fps = ffdkit.scenes.readScene(path).framesPerSecond
            objects, notes = scene_io.import_scene(bpy, ffdkit, path, context.collection)
        except (runtime.ModuleNotFound, tool_module.ToolError, OSError, ValueError) as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        if abs(fps - round(fps)) < 1e-9:
            context.scene.render.fps, context.scene.render.fps_base = int(round(fps)), 1.0
        else:
            notes.append("the scene's %g frames per second is not a whole number: Blender's frame rate left as it was" % fps)
        self.report({"WARNING"} if notes else {"INFO"},
                    "; ".join(["imported %d object(s) from %s" % (len(objects), bpy.path.basename(path))] + notes))
        return {"FINISHED"}


class FFDKIT_OT_export_scene(bpy.types.Operator):
    """Write the sliders' values and keys of the objects imported from an ffdkit scene back to a scene file"""

    bl_idname = "ffdkit.export_scene"
    bl_label = "Export ffdkit Scene"
    bl_options = {"REGISTER"}

    filepath: StringProperty(subtype="FILE_PATH")
    filter_glob: StringProperty(default="*.json", options={"HIDDEN"})

    @classmethod
    def poll(cls, context):
        return context.active_object is not None and scene_io.SCENE_KEY in context.active_object.keys()

    def invoke(self, context, event):
        self.filepath = scene_io.scene_file(context.active_object[scene_io.SCENE_KEY])
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def execute(self, context):
        obj = context.active_object
        if obj is None or scene_io.SCENE_KEY not in obj.keys():
            self.report({"ERROR"}, "the active object was not imported from an ffdkit scene")
            return {"CANCELLED"}
        source = obj[scene_io.SCENE_KEY]
        objects = [o for o in context.scene.objects if o.get(scene_io.SCENE_KEY) == source]
        fps = context.scene.render.fps / context.scene.render.fps_base
        try:
            notes = scene_io.export_scene(ffdkit_module(), objects, source, bpy.path.abspath(self.filepath), fps)
        except (runtime.ModuleNotFound, OSError, ValueError) as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        self.report({"WARNING"} if notes else {"INFO"}, "; ".join(["wrote %s" % self.filepath] + notes))
        return {"FINISHED"}


def _lattice_grid(lattice):
    """The rest grid of a Blender lattice (origin, spacing per axis) from its points' rest positions."""
    counts = (lattice.points_u, lattice.points_v, lattice.points_w)
    first = lattice.points[0].co
    steps = (1, counts[0], counts[0] * counts[1])
    origin = [first[a] for a in range(3)]
    spacing = [lattice.points[steps[a]].co[a] - first[a] if counts[a] > 1 else 1.0 for a in range(3)]
    return counts, origin, spacing


class FFDKIT_OT_export_lattice(bpy.types.Operator):
    """Write the active Lattice object as an ffdkit widget file that deforms as its Lattice modifier does"""

    bl_idname = "ffdkit.export_lattice"
    bl_label = "Export Lattice as ffdkit Widget File"
    bl_options = {"REGISTER"}

    filepath: StringProperty(subtype="FILE_PATH")
    filter_glob: StringProperty(default="*.json", options={"HIDDEN"})

    def invoke(self, context, event):
        if not self.filepath and context.active_object is not None:
            self.filepath = bpy.path.clean_name(context.active_object.name) + ".json"
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def execute(self, context):
        obj = context.active_object
        if obj is None or obj.type != "LATTICE":
            self.report({"ERROR"}, "the active object %s: select a Lattice object to export"
                        % ("is a %s" % obj.type.lower() if obj is not None else "is missing"))
            return {"CANCELLED"}
        lattice = obj.data
        counts, origin, spacing = _lattice_grid(lattice)
        points = [tuple(p.co_deform) for p in lattice.points]
        kinds = (lattice.interpolation_type_u, lattice.interpolation_type_v, lattice.interpolation_type_w)
        try:
            ffdkit = ffdkit_module()
            model = lattice_convert.widget_model_from_blender(ffdkit, obj.name, counts, kinds, origin, spacing, points,
                                                              [list(row) for row in obj.matrix_world])
            ffdkit.scenes.writeWidgetFile(bpy.path.abspath(self.filepath), model)
        except (runtime.ModuleNotFound, ValueError, OSError) as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        notes = []
        if lattice.vertex_group:
            notes.append("the lattice's vertex group '%s' (point weights) is not exported" % lattice.vertex_group)
        if lattice.shape_keys is not None or len(obj.modifiers) > 0:
            notes.append("the lattice's own shape keys and modifiers are not exported: its points as stored are")
        self.report({"WARNING"} if notes else {"INFO"}, "wrote %s%s" % (self.filepath, ("; " + "; ".join(notes)) if notes else ""))
        return {"FINISHED"}


class FFDKIT_OT_import_lattice(bpy.types.Operator):
    """Make Blender Lattice objects from the lattices of an ffdkit widget file (with a Lattice modifier on the active mesh)"""

    bl_idname = "ffdkit.import_lattice"
    bl_label = "Import ffdkit Lattices"
    bl_options = {"REGISTER", "UNDO"}

    filepath: StringProperty(subtype="FILE_PATH")
    filter_glob: StringProperty(default="*.json", options={"HIDDEN"})

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def execute(self, context):
        try:
            ffdkit = ffdkit_module()
            path = bpy.path.abspath(self.filepath)
            tool_module.read_widget_text(ffdkit, path)  # the file's errors, named as the user gave it
            model = ffdkit.scenes.readWidgetFile(path)
            converted = [(model.name(root), lattice_convert.blender_lattice_from_model(ffdkit, model, root))
                         for root in model.roots()]
        except (runtime.ModuleNotFound, tool_module.ToolError, lattice_convert.NotRepresentable) as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        target = context.active_object if context.active_object is not None and context.active_object.type == "MESH" else None
        warnings = []
        for name, blender in converted:
            data = bpy.data.lattices.new(name)
            data.points_u, data.points_v, data.points_w = blender.counts
            data.interpolation_type_u, data.interpolation_type_v, data.interpolation_type_w = blender.kinds
            for point, position in zip(data.points, blender.points):
                point.co_deform = tuple(position)
            obj = bpy.data.objects.new(name, data)
            context.collection.objects.link(obj)
            obj.matrix_world = mathutils.Matrix([list(row) for row in blender.matrix_world])  # rows, not RNA's column order
            if target is not None:
                modifier = target.modifiers.new(name, "LATTICE")
                modifier.object = obj
            warnings.extend(blender.warnings)
        message = "%d lattice(s) from %s%s" % (len(converted), bpy.path.basename(self.filepath),
                                               " onto '%s'" % target.name if target is not None else "")
        self.report({"WARNING"} if warnings else {"INFO"}, "; ".join([message] + warnings))
        return {"FINISHED"}


class FFDKIT_PT_tool(bpy.types.Panel):
    bl_label = "ffdkit"
    bl_idname = "FFDKIT_PT_tool"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "ffdkit"

    def draw(self, context):
        layout = self.layout
        obj = context.active_object
        layout.operator(FFDKIT_OT_load_tool.bl_idname, icon="FILEBROWSER")
        row = layout.row(align=True)
        row.operator(FFDKIT_OT_import_lattice.bl_idname, text="Import Lattices", icon="IMPORT")
        row.operator(FFDKIT_OT_export_lattice.bl_idname, text="Export Lattice", icon="EXPORT")
        row = layout.row(align=True)
        row.operator(FFDKIT_OT_import_scene.bl_idname, text="Import Scene", icon="IMPORT")
        row.operator(FFDKIT_OT_export_scene.bl_idname, text="Export Scene", icon="EXPORT")
        if not mesh_link.has_tool(obj):
            return
        layout.label(text=bpy.path.basename(obj.get(mesh_link.SOURCE_KEY, "")), icon="MOD_LATTICE")
        error = mesh_link.link_error(obj)
        if error:
            layout.label(text=error, icon="ERROR")
        column = layout.column(align=True)
        for key in obj.keys():
            if key.startswith(mesh_link.PREFIX):
                column.prop(obj, '["%s"]' % key, text=key[len(mesh_link.PREFIX):], slider=True)
        layout.operator(FFDKIT_OT_bake_shape_keys.bl_idname, icon="KEYINGSET")
        layout.operator(FFDKIT_OT_remove_tool.bl_idname, icon="X")


def _menu(self, context):
    self.layout.operator(FFDKIT_OT_load_tool.bl_idname)


def _sync_all(scene, depsgraph=None, new_frame=False):
    """Brings every tool on the scene's meshes up to date: before an evaluation (depsgraph None)
    from the objects' own values (on a new frame, keyed ones from their F-curves), so the shape
    key joins that evaluation; after it from the evaluated values (drivers), which costs one
    more evaluation only when a value changed."""
    try:
        ffdkit = ffdkit_module()
    except runtime.ModuleNotFound:
        return
    for obj in scene.objects:
        if mesh_link.has_tool(obj):
            evaluated = obj.evaluated_get(depsgraph) if depsgraph is not None else None
            mesh_link.sync(ffdkit, obj, evaluated, scene.frame_current if new_frame else None)


@persistent
def _before_evaluation(scene, *_):
    _sync_all(scene)


@persistent
def _before_frame(scene, *_):
    _sync_all(scene, new_frame=True)


@persistent
def _after_evaluation(scene, depsgraph=None, *_):
    _sync_all(scene, depsgraph)


@persistent
def _on_save(*_):
    try:
        mesh_link.store_states(ffdkit_module(), bpy.data.objects)
    except runtime.ModuleNotFound:
        pass


@persistent
def _on_load(_dummy):
    mesh_link.forget_all()


@persistent
def _on_undo(_scene):
    mesh_link.forget_all(mark_dirty_only=True)


# A slider dragged in the UI changes an ID property, which tags no depsgraph update, so no
# depsgraph handler runs: the interface is polled as well (a few property reads per tool).
POLL_SECONDS = 0.05


def _poll():
    scene = bpy.context.scene
    if scene is not None:
        _sync_all(scene)
    return POLL_SECONDS


_classes = (FFDKIT_AP_preferences, FFDKIT_OT_load_tool, FFDKIT_OT_remove_tool, FFDKIT_OT_bake_shape_keys,
            FFDKIT_OT_export_lattice,
            FFDKIT_OT_import_lattice, FFDKIT_OT_import_scene, FFDKIT_OT_export_scene, FFDKIT_PT_tool)
_handlers = (
    (bpy.app.handlers.depsgraph_update_pre, _before_evaluation),
    (bpy.app.handlers.frame_change_pre, _before_frame),
    (bpy.app.handlers.depsgraph_update_post, _after_evaluation),
    (bpy.app.handlers.frame_change_post, _after_evaluation),
    (bpy.app.handlers.load_post, _on_load),
    (bpy.app.handlers.save_pre, _on_save),
    (bpy.app.handlers.undo_post, _on_undo),
    (bpy.app.handlers.redo_post, _on_undo),
)


def register():
    for cls in _classes:
        bpy.utils.register_class(cls)
    bpy.types.VIEW3D_MT_object.append(_menu)
    for handlers, function in _handlers:
        if function not in handlers:
            handlers.append(function)
    if not bpy.app.timers.is_registered(_poll):
        bpy.app.timers.register(_poll, first_interval=POLL_SECONDS, persistent=True)


def unregister():
    if bpy.app.timers.is_registered(_poll):
        bpy.app.timers.unregister(_poll)
    for handlers, function in _handlers:
        if function in handlers:
            handlers.remove(function)
    bpy.types.VIEW3D_MT_object.remove(_menu)
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
    mesh_link.forget_all()
