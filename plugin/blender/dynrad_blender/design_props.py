"""The lighting design's settings, stored in the .blend file:

- on each light (Object Data > dynrad luminaire): its IES/LDT file, flux and
  maintenance factor (DynradLuminaire, bpy.types.Light.dynrad);
- on each mesh object (Object > dynrad work plane): whether it is a work plane, with
  its grid's spacing, border and targets (DynradWorkPlane, bpy.types.Object.dynrad_plane);
- on the scene (sidebar > dynrad > Sky and sun): the sky, the sun, the ground, and the
  design solve's outputs (DynradDesign, bpy.types.Scene.dynrad_design).

Each default is the scene file's (docs/scene-reference.md), so an untouched field writes
nothing into the scene file and dynrad chooses as `dynrad solve` does.
"""

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, StringProperty


class DynradLuminaire(bpy.types.PropertyGroup):
    enabled: BoolProperty(
        name="dynrad luminaire",
        description="Light the design with this light (off: dynrad ignores it)",
        default=True)
    photometry: StringProperty(
        name="Photometry",
        subtype="FILE_PATH",
        description="IES (LM-63) or EULUMDAT (.ldt) file; empty: a Point light is an isotropic point and a Spot "
                    "light a cone of its size and blend, both of the flux below")
    lumens: FloatProperty(
        name="Lumens",
        description="Flux in lm (0: the photometry file's). Required without a file; Blender's Power is not used",
        default=0.0, min=0.0)
    maintenance_factor: FloatProperty(
        name="Maintenance factor", description="Multiplies the flux (EN 12464-1's MF)", default=1.0, min=0.01,
        max=1.0)
    watts: FloatProperty(name="Watts", description="Electrical power for the schedule (0: not given)", default=0.0,
                         min=0.0)


class DynradWorkPlane(bpy.types.PropertyGroup):
    is_work_plane: BoolProperty(
        name="Work plane",
        description="A calculation grid over this object's outline in plan, at its height; it is not lit as a "
                    "surface. The object must be flat and horizontal (a Plane)",
        default=False)
    spacing: FloatProperty(
        name="Spacing", description="Between grid points (0: dynrad's automatic spacing)", default=0.0, min=0.0,
        unit="LENGTH")
    border: FloatProperty(name="Border", description="Band along the edges left out", default=0.0, min=0.0,
                          unit="LENGTH")
    target_eavg: FloatProperty(name="Target Eavg", description="Maintained illuminance to check, lx (0: none)",
                               default=0.0, min=0.0)
    target_u0: FloatProperty(name="Target U0", description="Uniformity Emin/Eavg to check (0: none)", default=0.0,
                             min=0.0, max=1.0)


class DynradDesign(bpy.types.PropertyGroup):
    sky: EnumProperty(
        name="Sky",
        items=[
            ("none", "None", "No daylight"),
            ("cie_overcast", "CIE overcast", "The CIE standard overcast sky"),
            ("cie", "CIE general", "One of the 15 CIE standard general skies (ISO 15469)"),
            ("uniform", "Uniform", "The same luminance in every direction"),
        ],
        default="none")
    cie_number: IntProperty(name="CIE sky", description="CIE standard general sky 1 to 15", default=12, min=1,
                            max=15)
    horizontal_illuminance: FloatProperty(
        name="Sky illuminance", description="The sky's unobstructed horizontal illuminance, lx", default=10000.0,
        min=0.001)
    ground_reflectance: FloatProperty(name="Ground reflectance", default=0.2, min=0.0, max=0.99)
    north: FloatProperty(
        name="North", description="North's direction in plan, clockwise from +Y (0: +Y is north)", default=0.0,
        subtype="ANGLE")
    sun: EnumProperty(
        name="Sun",
        items=[
            ("none", "None", "No sun"),
            ("angles", "Altitude and azimuth", "Where the sun is"),
            ("place", "Place and time", "The sun of a site at a local standard time"),
        ],
        default="none")
    altitude: FloatProperty(name="Altitude", default=0.7, min=0.0, max=1.5708, subtype="ANGLE")
    azimuth: FloatProperty(name="Azimuth", description="Clockwise from north", default=3.1416, subtype="ANGLE")
    latitude: FloatProperty(name="Latitude", description="Degrees, north positive", default=47.0, min=-90, max=90)
    longitude: FloatProperty(name="Longitude", description="Degrees, east positive", default=7.5, min=-180, max=180)
    time: StringProperty(name="Time", description="Local standard time, YYYY-MM-DDTHH:MM", default="2024-06-21T12:00")
    timezone: FloatProperty(name="Time zone", description="Hours east of UTC", default=1.0, min=-12, max=14)
    direct_normal: FloatProperty(
        name="Sun illuminance",
        description="Direct normal illuminance of the sun, lx (0: the sun only shapes a CIE sky and sends nothing)",
        default=0.0, min=0.0)
    sky_rays: IntProperty(name="Sky rays", description="Sky directions per point, this number squared",
                          default=32, min=4, max=256)

    folder: StringProperty(
        name="Scene folder", subtype="DIR_PATH",
        description="Where the model and scene file dynrad reads are written (empty: a new temporary folder)")
    report_path: StringProperty(
        name="HTML report", subtype="FILE_PATH",
        description="Also write the lighting report here, with its pictures beside it (empty: no report)")
    scale_max: FloatProperty(
        name="Scale top", description="Illuminance shown red in the false colours, lx (0: a round number at or "
                                      "above the grids' Emax, else the surfaces' 98th percentile)",
        default=0.0, min=0.0)
    last_scene_file: StringProperty(name="Last scene file", default="")
    last_scale: StringProperty(name="Last scale", default="")
    last_summary: StringProperty(name="Last result", default="")


classes = (DynradLuminaire, DynradWorkPlane, DynradDesign)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    bpy.types.Light.dynrad = bpy.props.PointerProperty(type=DynradLuminaire)
    bpy.types.Object.dynrad_plane = bpy.props.PointerProperty(type=DynradWorkPlane)
    bpy.types.Scene.dynrad_design = bpy.props.PointerProperty(type=DynradDesign)


def unregister():
    del bpy.types.Scene.dynrad_design
    del bpy.types.Object.dynrad_plane
    del bpy.types.Light.dynrad
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
