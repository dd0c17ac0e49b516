"""The lighting design in Blender's interface: the operator that lights the design
(View3D > Sidebar > dynrad > Lighting design, or Object > Light the design with dynrad)
and the panels of its settings (design_props.py).

The operator writes the scene (design.py) into the scene folder, loads it with
dynrad_scene_load and solves it with the sidebar's solve settings (scene.dynrad), as
`dynrad solve FOLDER/design.json` would, writes the HTML report when a path is set,
then adds the result objects (design_results.py). On any error it reports it (naming the
object and what to do) and changes nothing in the .blend.
"""

import os
import tempfile

import bpy

from . import capi, design, design_results


def load_library(context):
    preferences = context.preferences.addons.get(__package__)
    explicit = bpy.path.abspath(preferences.preferences.library_path) if preferences else ""
    return capi.Library(explicit)


def summary(result, top, unit):
    r = result.report
    grids = ", ".join("%s Eavg %.4g %s" % (g.get("name"), g.get("Eavg", float("nan")), unit)
                      for g in result.report_json.get("grids", []))
    return "%d shots, %s, %.1f s%s; false colours 0 to %.4g %s" % (
        r["shots"], r["stopped_by"], r["seconds"], "; " + grids if grids else "", top, unit)


class DYNRAD_OT_light_design(bpy.types.Operator):
    bl_idname = "scene.dynrad_light_design"
    bl_label = "Light the design with dynrad"
    bl_description = ("Light the visible objects with their luminaires, sky and sun; show illuminance in false "
                      "colour and each work plane's grid; write the HTML report when a path is set")
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return context.mode == "OBJECT"

    def execute(self, context):
        settings = context.scene.dynrad
        design_settings = context.scene.dynrad_design
        try:
            library = load_library(context)
            model, scene = design.build_scene(context)
            folder = bpy.path.abspath(design_settings.folder) if design_settings.folder else \
                tempfile.mkdtemp(prefix="dynrad_design_")
            path = design.write_scene(model, scene, folder)
            report_path = bpy.path.abspath(design_settings.report_path) if design_settings.report_path else None
            result = capi.solve_file(library, path, settings.options(), report_path)
        except (design.DesignError, capi.DynradError, OSError) as error:
            self.report({"ERROR"}, "dynrad: %s" % error)
            return {"CANCELLED"}
        name = file_name_of_scene(context) + "_dynrad"
        lit, grids, top = design_results.add_result_objects(context, library, result, name,
                                                            design_settings.scale_max)
        lit["dynrad_scene_file"] = path
        if report_path:
            lit["dynrad_report"] = report_path
        for other in context.selected_objects:
            other.select_set(False)
        lit.select_set(True)
        context.view_layer.objects.active = lit
        screen = getattr(context, "screen", None)
        for area in screen.areas if screen else []:
            if area.type == "VIEW_3D":
                area.spaces.active.shading.color_type = "VERTEX"
        unit = lit["dynrad_unit"]
        design_settings.last_scene_file = path
        design_settings.last_scale = "0 to %.4g %s (dark blue to red)" % (top, unit)
        design_settings.last_summary = summary(result, top, unit)
        self.report({"INFO"}, "dynrad: " + design_settings.last_summary)
        return {"FINISHED"}


def file_name_of_scene(context):
    return design.file_name(context.scene.name)


class DYNRAD_PT_design(bpy.types.Panel):
    bl_label = "Lighting design"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "dynrad"

    def draw(self, context):
        d = context.scene.dynrad_design
        layout = self.layout
        box = layout.box()
        box.label(text="Sky and sun")
        box.prop(d, "sky")
        if d.sky != "none":
            if d.sky == "cie":
                box.prop(d, "cie_number")
            for name in ("horizontal_illuminance", "ground_reflectance", "north", "sky_rays", "sun"):
                box.prop(d, name)
            if d.sun == "angles":
                box.prop(d, "altitude")
                box.prop(d, "azimuth")
            elif d.sun == "place":
                for name in ("latitude", "longitude", "time", "timezone"):
                    box.prop(d, name)
            if d.sun != "none":
                box.prop(d, "direct_normal")
        for name in ("folder", "report_path", "scale_max"):
            layout.prop(d, name)
        layout.operator(DYNRAD_OT_light_design.bl_idname, icon="LIGHT_AREA")
        if d.last_summary:
            layout.label(text=d.last_summary)
            layout.label(text="False colours: " + d.last_scale)


class DYNRAD_PT_luminaire(bpy.types.Panel):
    bl_label = "dynrad luminaire"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "data"

    @classmethod
    def poll(cls, context):
        return context.light is not None

    def draw_header(self, context):
        self.layout.prop(context.light.dynrad, "enabled", text="")

    def draw(self, context):
        settings = context.light.dynrad
        for name in ("photometry", "lumens", "maintenance_factor", "watts"):
            self.layout.prop(settings, name)


class DYNRAD_PT_work_plane(bpy.types.Panel):
    bl_label = "dynrad work plane"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "object"

    @classmethod
    def poll(cls, context):
        return context.object is not None and context.object.type == "MESH"

    def draw_header(self, context):
        self.layout.prop(context.object.dynrad_plane, "is_work_plane", text="")

    def draw(self, context):
        settings = context.object.dynrad_plane
        for name in ("spacing", "border", "target_eavg", "target_u0"):
            self.layout.prop(settings, name)


def menu_entry(self, context):
    self.layout.operator(DYNRAD_OT_light_design.bl_idname)


classes = (DYNRAD_OT_light_design, DYNRAD_PT_design, DYNRAD_PT_luminaire, DYNRAD_PT_work_plane)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    bpy.types.VIEW3D_MT_object.append(menu_entry)


def unregister():
    bpy.types.VIEW3D_MT_object.remove(menu_entry)
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
