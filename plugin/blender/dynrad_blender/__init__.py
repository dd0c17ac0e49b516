"""dynrad for Blender: light the selected objects with radiosity.

The operator (Object > Light with dynrad, or the dynrad tab of the 3D view's sidebar)
reads the selected mesh objects in world space with their modifiers applied, takes
each material's diffuse reflectance and emission from its Principled BSDF, calls
libdynrad.so through ctypes (capi.py) and adds a new object holding the refined mesh
with two colour attributes on its points:

- `radiosity`: linear radiosity (W/m^2 when the emission is read as W/m^2), a float
  colour, for scripts, baking and shading (Attribute node);
- `radiosity_display`: the command line's display colours (radiosity times an
  exposure, sRGB-encoded), a byte colour, made active so that Solid mode with
  Attribute colouring shows the lighting at once.

Materials. Reflectance = Base Color (linear), each channel clamped to at most 0.95: a
white base colour is a display choice, not a perfect mirror, and the C ABI refuses
reflectance >= 1 (dynrad's file readers lower it to 0.95 too, with a warning). Emission = Emission colour x Emission Strength, read as radiant
exitance in W/m^2 leaving the front of the face, exactly as dynrad reads Ke from an
MTL file (Blender's OBJ importer puts Ke into the Emission colour). An Emission shader
gives Color x Strength with reflectance 0. Without nodes: the viewport colour as
reflectance, no emission. A face's front is where its normal points.

The library is found through the add-on preference "Library", else $DYNRAD_LIBRARY,
else libdynrad.so beside this file, else the system's library path.
"""

import ctypes
import threading

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, PointerProperty, StringProperty

from . import capi, design_props, design_results, design_ui

bl_info = {
    "name": "dynrad radiosity",
    "author": "dynrad",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > dynrad; Object > Light with dynrad",
    "description": "Light the selected objects with radiosity (Dynamic Subdivision, Dubuis & Bieri)",
    "category": "Lighting",
}

from .materials import DEFAULT_REFLECTANCE, MAX_REFLECTANCE, material_values  # noqa: F401 (the tests use them)


# ---------------------------------------------------------------------------
# Settings


class DynradPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    library_path: StringProperty(
        name="Library",
        subtype="FILE_PATH",
        description="Path of libdynrad.so (empty: $DYNRAD_LIBRARY, beside the add-on, or the system's path)",
    )

    def draw(self, context):
        self.layout.prop(self, "library_path")


class DynradSettings(bpy.types.PropertyGroup):
    method: EnumProperty(
        name="Method",
        items=[
            ("progressive", "Progressive", "Shoot to the initial patches (Cohen et al. 1988)"),
            ("adaptive", "Adaptive", "Refine receivers by cumulated gradient (Cohen et al. 1986)"),
            ("dynamic", "Dynamic", "Decide per sender where to refine (Dubuis & Bieri)"),
        ],
        default="dynamic",
    )
    quality: EnumProperty(
        name="Quality",
        items=[
            ("draft", "Draft", "Stop at about 3% estimated error"),
            ("normal", "Normal", "Stop at about 1% estimated error (the default)"),
            ("high", "High", "Stop at about 0.3% estimated error"),
        ],
        default="normal",
    )
    max_level: IntProperty(name="Max level",
                           description="1 -> 4 splits allowed below a patch (-1: the quality's; 3 for progressive "
                                       "and adaptive)", default=-1, min=-1, max=12)
    patch_size: FloatProperty(
        name="Patch size",
        description="Longest patch edge in scene units (0: from the model and the quality; progressive and "
                    "adaptive: a tenth of the bounding-box diagonal)",
        default=0.0, min=0.0, unit="LENGTH")
    converge: FloatProperty(name="Converge",
                            description="Stop when unshot power is below this fraction of emitted (0: stop by the "
                                        "quality's error target; progressive and adaptive: 0.01)",
                            default=0.0, min=0.0, max=0.999, precision=4)
    iterations: IntProperty(name="Shots", description="Stop after this many shots (0: no limit)", default=0, min=0)
    time_limit: FloatProperty(name="Time limit", description="Stop after this many seconds (0: no limit)",
                              default=0.0, min=0.0, unit="TIME_ABSOLUTE")
    threads: IntProperty(name="Threads", description="Worker threads (0: all cores)", default=0, min=0, max=1024)
    seed: IntProperty(name="Seed", description="Seed of all ray sampling", default=1, min=0)
    ambient: BoolProperty(
        name="Ambient term",
        description="Add the estimate of light not yet shot to the result, so that a solve stopped early "
                    "(Esc, a time limit) looks close to the converged one",
        default=True)
    simplify: BoolProperty(
        name="Merge flat regions",
        description="Merge the triangles of flat regions before patching (lossless for the light; "
                    "off keeps every triangle, as dynrad solve --no-simplify)",
        default=True)
    # Refinement: the command line's --threshold, --oracle, --pushdown-error,
    # --pushdown-floor and --max-elements, with its defaults.
    threshold: FloatProperty(
        name="Gradient threshold",
        description="Adaptive: refine where the cumulated radiosity's corners differ by more than this "
                    "fraction; also all three of the paper oracle's thresholds",
        default=0.25, min=0.001, max=1.0, precision=3)
    oracle: EnumProperty(
        name="Oracle",
        items=[
            ("pushdown", "Push-down", "Refine where pushing this sender's light down would leave more than "
                                      "the push-down error (the default)"),
            ("paper", "Paper", "Figure 6 of Dubuis & Bieri: three gradient conditions"),
        ],
        default="pushdown")
    pushdown_error: FloatProperty(
        name="Push-down error",
        description="Largest error, as a fraction of a transfer, left where refinement stops (smaller: finer "
                    "and slower; 0: the quality's)",
        default=0.0, min=0.0, max=1.0, precision=3)
    pushdown_floor: FloatProperty(
        name="Push-down floor",
        description="Transfers below this fraction of an element's brightness do not refine it (0: the quality's)",
        default=0.0, min=0.0, max=1.0, precision=3)
    max_elements: IntProperty(
        name="Max elements", description="Stop refining at this many elements (0: no limit)", default=0, min=0)
    overshoot: FloatProperty(
        name="Overshoot",
        description="Over-relax each shot by this factor (1: plain progressive refinement; 1.3 needs fewer shots)",
        default=1.0, min=0.05, max=1.95, precision=2)
    shaped_senders: BoolProperty(
        name="Shaped senders",
        description="Shoot each patch's light shaped by its corners and a quarter grid of points (off: evenly, as "
                    "dynrad solve --flat-senders)",
        default=True)
    last_report: StringProperty(name="Last report", default="")

    def options(self):
        # Left out where the quality chooses (as `dynrad solve` without the option).
        chosen = {"max_level": self.max_level < 0, "converge": self.converge == 0,
                  "pushdown_error": self.pushdown_error == 0, "pushdown_floor": self.pushdown_floor == 0}
        options = {
            "method": self.method,
            "quality": self.quality,
            "max_level": self.max_level,
            "patch_size": self.patch_size,
            "converge": self.converge,
            "iterations": self.iterations,
            "time_limit": self.time_limit,
            "threads": self.threads,
            "seed": self.seed,
            "ambient": int(self.ambient),
            "simplify": int(self.simplify),
            "threshold": self.threshold,
            "oracle": self.oracle,
            "pushdown_error": self.pushdown_error,
            "pushdown_floor": self.pushdown_floor,
            "max_elements": self.max_elements,
            "overshoot": self.overshoot,
            "shaped_senders": int(self.shaped_senders),
        }
        return {name: value for name, value in options.items() if not chosen.get(name, False)}


def load_library(context):
    preferences = context.preferences.addons.get(__package__)
    explicit = bpy.path.abspath(preferences.preferences.library_path) if preferences else ""
    return capi.Library(explicit)


# ---------------------------------------------------------------------------
# Reading the scene


class Soup:
    """The selected objects as one polygon soup in world space, with their materials."""

    def __init__(self):
        self.positions = []
        self.sizes = []
        self.indices = []
        self.face_materials = []
        self.materials = []  # (name, reflectance, emission) for the library
        self.blender_materials = []  # the Blender material of each entry, or None
        self._material_index = {}

    def material_index(self, material):
        key = material.name if material else None
        if key not in self._material_index:
            reflectance, emission = material_values(material)
            self._material_index[key] = len(self.materials)
            self.materials.append((material.name if material else "default", reflectance, emission))
            self.blender_materials.append(material)
        return self._material_index[key]

    def add_object(self, obj, depsgraph):
        evaluated = obj.evaluated_get(depsgraph)
        mesh = evaluated.to_mesh()
        try:
            mesh.transform(obj.matrix_world)
            mirrored = obj.matrix_world.determinant() < 0  # keep each face's front side
            first = len(self.positions) // 3
            co = [0.0] * (3 * len(mesh.vertices))
            mesh.vertices.foreach_get("co", co)
            self.positions.extend(co)
            slots = [self.material_index(slot.material) for slot in obj.material_slots] or [self.material_index(None)]
            for polygon in mesh.polygons:
                loop = [first + v for v in polygon.vertices]
                if mirrored:
                    loop.reverse()
                self.sizes.append(len(loop))
                self.indices.extend(loop)
                self.face_materials.append(slots[min(polygon.material_index, len(slots) - 1)])
        finally:
            evaluated.to_mesh_clear()


def selected_meshes(context):
    return [o for o in context.selected_objects if o.type == "MESH"]


# ---------------------------------------------------------------------------
# Writing the result


def add_result_object(context, result, soup, name):
    """A new object with the refined mesh, its materials and both colour attributes."""
    mesh = design_results.triangle_mesh(name, result)
    for material in soup.blender_materials:
        mesh.materials.append(material)
    mesh.polygons.foreach_set("material_index", result.triangle_materials)
    mesh.update()
    mesh.validate()

    design_results.radiosity_attributes(mesh, result)
    mesh.color_attributes.active_color = mesh.color_attributes["radiosity_display"]
    mesh.color_attributes.render_color_index = mesh.color_attributes.find("radiosity_display")

    obj = bpy.data.objects.new(name, mesh)
    context.scene.collection.objects.link(obj)
    for key in ("shots", "unshot_fraction", "seconds", "exposure", "patch_size", "energy_transfers"):
        obj["dynrad_" + key] = result.report[key]
    obj["dynrad_stopped_by"] = result.report["stopped_by"]
    return obj


def show_attribute_colours(context):
    """Solid mode with attribute colours in every 3D view, so the result shows at once."""
    screen = getattr(context, "screen", None)
    for area in screen.areas if screen else []:
        if area.type == "VIEW_3D":
            area.spaces.active.shading.color_type = "VERTEX"


def summary(result):
    r = result.report
    return "%d shots, unshot %.2f%%, %s, %.1f s, %d patches, %d triangles" % (
        r["shots"], 100 * r["unshot_fraction"], r["stopped_by"], r["seconds"], r["patches"], result.triangle_count)


# ---------------------------------------------------------------------------
# The operator: execute() solves at once (scripts, background mode); invoke() solves
# in a worker thread so the interface stays responsive, and Esc stops the solve at
# the next shot boundary, keeping the solution so far.


class DYNRAD_OT_light(bpy.types.Operator):
    bl_idname = "object.dynrad_light"
    bl_label = "Light with dynrad"
    bl_description = "Compute radiosity on the selected objects into a new object with a 'radiosity' colour attribute"
    bl_options = {"REGISTER", "UNDO"}

    _thread = None
    _timer = None

    @classmethod
    def poll(cls, context):
        return context.mode == "OBJECT" and bool(selected_meshes(context))

    def prepare(self, context):
        self.library = load_library(context)
        self.soup = Soup()
        depsgraph = context.evaluated_depsgraph_get()
        objects = selected_meshes(context)
        for obj in objects:
            self.soup.add_object(obj, depsgraph)
        self.result_name = (objects[0].name if len(objects) == 1 else "scene") + "_radiosity"
        self.settings = context.scene.dynrad
        self.progress = (0, 1.0)
        self.cancel = ctypes.c_int(0)

    def run_solve(self):
        def on_progress(shot, unshot):
            self.progress = (shot, unshot)
            return False

        s = self.soup
        return capi.solve(self.library, s.positions, s.sizes, s.indices, s.face_materials, s.materials,
                          self.settings.options(), on_progress, self.cancel)

    def finish(self, context, result):
        obj = add_result_object(context, result, self.soup, self.result_name)
        for other in context.selected_objects:
            other.select_set(False)
        obj.select_set(True)
        context.view_layer.objects.active = obj
        show_attribute_colours(context)
        text = summary(result)
        self.settings.last_report = text
        self.report({"WARNING"} if result.stopped else {"INFO"},
                    ("stopped early: " if result.stopped else "dynrad: ") + text)
        return {"FINISHED"}

    def execute(self, context):
        try:
            self.prepare(context)
            return self.finish(context, self.run_solve())
        except capi.DynradError as error:
            self.report({"ERROR"}, "dynrad: %s" % error)
            return {"CANCELLED"}

    def invoke(self, context, event):
        try:
            self.prepare(context)
        except capi.DynradError as error:
            self.report({"ERROR"}, "dynrad: %s" % error)
            return {"CANCELLED"}
        self.outcome = None

        def work():
            try:
                self.outcome = self.run_solve()
            except Exception as error:  # handed to the main thread, reported there
                self.outcome = error

        self._thread = threading.Thread(target=work, daemon=True)
        self._thread.start()
        self._timer = context.window_manager.event_timer_add(0.2, window=context.window)
        context.window_manager.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        if event.type == "ESC":
            self.cancel.value = 1  # the solve stops at the next shot boundary
            return {"RUNNING_MODAL"}
        if event.type != "TIMER":
            return {"PASS_THROUGH"}  # the interface stays usable while the solve runs
        shot, unshot = self.progress
        context.workspace.status_text_set("dynrad: shot %d, unshot %.2f%% (Esc: stop and keep)" % (shot, 100 * unshot))
        if self._thread.is_alive():
            return {"RUNNING_MODAL"}
        context.window_manager.event_timer_remove(self._timer)
        context.workspace.status_text_set(None)
        if isinstance(self.outcome, capi.DynradError):
            self.report({"ERROR"}, "dynrad: %s" % self.outcome)
            return {"CANCELLED"}
        if isinstance(self.outcome, Exception):
            raise self.outcome
        return self.finish(context, self.outcome)


class DYNRAD_PT_panel(bpy.types.Panel):
    bl_label = "dynrad radiosity"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "dynrad"

    def draw(self, context):
        settings = context.scene.dynrad
        layout = self.layout
        for name in ("quality", "method", "max_level", "patch_size", "converge", "ambient", "simplify"):
            layout.prop(settings, name)
        if settings.method != "progressive":
            box = layout.box()
            box.label(text="Refinement")
            names = ["threshold"] if settings.method == "adaptive" else ["oracle"]
            if settings.method == "dynamic":
                names += ["pushdown_error", "pushdown_floor"] if settings.oracle == "pushdown" else ["threshold"]
            for name in names + ["max_elements"]:
                box.prop(settings, name)
        box = layout.box()
        box.label(text="Stop rules and sampling")
        for name in ("iterations", "time_limit", "overshoot", "shaped_senders", "threads", "seed"):
            box.prop(settings, name)
        layout.operator(DYNRAD_OT_light.bl_idname, icon="LIGHT_SUN")
        if settings.last_report:
            layout.label(text=settings.last_report)


def menu_entry(self, context):
    self.layout.operator(DYNRAD_OT_light.bl_idname)


classes = (DynradPreferences, DynradSettings, DYNRAD_OT_light, DYNRAD_PT_panel)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    bpy.types.Scene.dynrad = PointerProperty(type=DynradSettings)
    bpy.types.VIEW3D_MT_object.append(menu_entry)
    design_props.register()
    design_ui.register()


def unregister():
    design_ui.unregister()
    design_props.unregister()
    bpy.types.VIEW3D_MT_object.remove(menu_entry)
    del bpy.types.Scene.dynrad
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
