"""A Blender scene as a dynrad scene file: what the design operator hands to
dynrad_scene_load, so that the add-on and `dynrad solve` read one file.

Written into a folder: design.obj + design.mtl (the visible mesh objects in world space,
every digit, each material's reflectance and emission) and design.json (the model, the
luminaires from the light objects, the sky and the sun from the scene's settings, a
grid per work plane). Every check that can fail is made before anything is written;
DesignError names the object and says what to do.
"""

import json
import math
import os
import re

import bpy
from mathutils import Vector

from .materials import material_values

FLAT = 1e-4  # a work plane's height may vary by this fraction of its size


class DesignError(ValueError):
    """Something in the Blender scene dynrad cannot light; the message names it."""


def file_name(name):
    """A name safe in file names and OBJ/MTL statements (the grids' pictures are named after it)."""
    return re.sub(r"[^A-Za-z0-9_.-]", "_", name) or "unnamed"


def is_result(obj):
    """An object the add-on made: a design result, or the light operator's (dynrad_shots)."""
    return bool(obj.get("dynrad_result")) or "dynrad_shots" in obj


def design_objects(context):
    """(meshes lit, light objects, work planes): the visible objects of the view layer;
    earlier results of the add-on are left out."""
    visible = [o for o in context.view_layer.objects if o.visible_get() and not is_result(o)]
    planes = [o for o in visible if o.type == "MESH" and o.dynrad_plane.is_work_plane]
    meshes = [o for o in visible if o.type == "MESH" and not o.dynrad_plane.is_work_plane]
    lights = [o for o in visible if o.type == "LIGHT" and o.data.dynrad.enabled]
    return meshes, lights, planes


# ---------------------------------------------------------------------------
# The model


class Model:
    """The meshes' polygons in world space with their materials, ready to write."""

    def __init__(self):
        self.positions = []  # Vector per vertex
        self.faces = []  # (material index, vertex indices)
        self.materials = []  # (OBJ name, reflectance, emission)
        self._index = {}

    def material(self, obj, material):
        key = material.name if material else None
        if key not in self._index:
            reflectance, emission = material_values(material, clamp=False)
            if max(reflectance) >= 1:
                raise DesignError(
                    "object '%s', material '%s': reflectance %s is 1 or more, which would create light. Lower its "
                    "Base Color below 1 in every channel (0.8 for white paint)."
                    % (obj.name, key, ", ".join("%.3g" % c for c in reflectance)))
            self._index[key] = len(self.materials)
            self.materials.append(("m%d_%s" % (len(self.materials), file_name(key or "default")), reflectance,
                                   emission))
        return self._index[key]

    def add(self, obj, depsgraph):
        evaluated = obj.evaluated_get(depsgraph)
        mesh = evaluated.to_mesh()
        try:
            matrix = obj.matrix_world
            mirrored = matrix.determinant() < 0  # keep each face's front side
            first = len(self.positions)
            self.positions.extend(matrix @ v.co for v in mesh.vertices)
            slots = [self.material(obj, s.material) for s in obj.material_slots] or [self.material(obj, None)]
            for polygon in mesh.polygons:
                loop = [first + v for v in polygon.vertices]
                if mirrored:
                    loop.reverse()
                self.faces.append((slots[min(polygon.material_index, len(slots) - 1)], loop))
        finally:
            evaluated.to_mesh_clear()

    def write(self, stem):
        """stem.obj and stem.mtl; returns the OBJ's file name."""
        with open(stem + ".mtl", "w") as mtl:
            for name, reflectance, emission in self.materials:
                mtl.write("newmtl %s\nKd %r %r %r\nKe %r %r %r\n" % ((name,) + tuple(reflectance) + tuple(emission)))
        with open(stem + ".obj", "w") as obj:
            obj.write("# written by the dynrad Blender add-on\nmtllib %s.mtl\n" % os.path.basename(stem))
            for p in self.positions:
                obj.write("v %r %r %r\n" % (p.x, p.y, p.z))
            current = None
            for material, loop in self.faces:
                if material != current:
                    obj.write("usemtl %s\n" % self.materials[material][0])
                    current = material
                obj.write("f %s\n" % " ".join(str(v + 1) for v in loop))
        return os.path.basename(stem) + ".obj"


# ---------------------------------------------------------------------------
# Luminaires, sky, grids


def _vector(v):
    return [float(v[0]), float(v[1]), float(v[2])]


def luminaire_entry(obj):
    """A light object as an entry of the scene file's "luminaires"."""
    light, settings = obj.data, obj.data.dynrad
    matrix = obj.matrix_world
    rotation = matrix.to_3x3().normalized()
    aim = (rotation @ Vector((0, 0, -1))).normalized()  # Blender's lights shine along their -Z
    entry = {"name": obj.name, "position": _vector(matrix.translation)}
    if settings.maintenance_factor != 1:
        entry["maintenance_factor"] = settings.maintenance_factor
    if settings.watts > 0:
        entry["watts"] = settings.watts
    if settings.lumens > 0:
        entry["lumens"] = settings.lumens
    if settings.photometry:
        path = os.path.abspath(bpy.path.abspath(settings.photometry))
        if not os.path.isfile(path):
            raise DesignError("light '%s': its photometry file '%s' does not exist. Choose an IES or LDT file in "
                              "the light's dynrad luminaire panel (Object Data), or clear the field." % (obj.name, path))
        entry["type"] = "photometric"
        entry["photometry"] = path
    elif light.type in ("POINT", "SPOT"):
        if settings.lumens <= 0:
            raise DesignError("light '%s' has neither a photometry file nor lumens. Set an IES or LDT file, or its "
                              "lumens, in the light's dynrad luminaire panel (Object Data), or untick 'dynrad "
                              "luminaire' there." % obj.name)
        entry["type"] = "point" if light.type == "POINT" else "spot"
        if light.type == "SPOT":
            outer = math.degrees(light.spot_size) / 2
            entry["cone"] = [outer * (1 - light.spot_blend), outer]
    else:
        raise DesignError("light '%s' is a %s light without a photometry file. Give it an IES or LDT file in the "
                          "dynrad luminaire panel (Object Data), or untick 'dynrad luminaire'; the sun is set in "
                          "the sidebar's dynrad design panel." % (obj.name, light.type.title()))
    if entry["type"] != "point":
        entry["aim"] = _vector(aim)
        # The spin that turns dynrad's C0 (+x made perpendicular to the aim) to the light's
        # local +X, counter-clockwise seen from behind (luminaire.h).
        reference = Vector((1, 0, 0)) if abs(aim.x) < 0.999 else Vector((0, 1, 0))
        c0 = (reference - aim * reference.dot(aim)).normalized()
        c90 = (-aim).cross(c0)
        x = rotation @ Vector((1, 0, 0))
        spin = math.degrees(math.atan2(x.dot(c90), x.dot(c0)))
        if abs(spin) > 1e-9:
            entry["spin"] = spin
    return entry


def sky_entry(design):
    """The scene file's "sky" from the scene's settings, or None."""
    if design.sky == "none":
        if design.sun != "none":
            raise DesignError("the dynrad design panel sets a sun but no sky. Choose a sky (the sun shapes it), or "
                              "set Sun to None.")
        return None
    sky = {"type": design.sky, "horizontal_illuminance": design.horizontal_illuminance,
           "ground_reflectance": design.ground_reflectance, "rays": design.sky_rays}
    if design.sky == "cie":
        sky["number"] = design.cie_number
    if design.north != 0:
        sky["north"] = [math.sin(design.north), math.cos(design.north)]
    if design.sun != "none":
        if design.sun == "angles":
            sun = {"altitude": math.degrees(design.altitude), "azimuth": math.degrees(design.azimuth) % 360}
        else:
            if not re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d", design.time):
                raise DesignError("the dynrad design panel's sun time '%s' is not YYYY-MM-DDTHH:MM (for example "
                                  "2024-06-21T12:00)." % design.time)
            sun = {"latitude": design.latitude, "longitude": design.longitude, "time": design.time,
                   "timezone": design.timezone}
        if design.direct_normal > 0:
            sun["direct_normal"] = design.direct_normal
        sky["sun"] = sun
    return sky


def grid_entry(obj):
    """A work plane as an entry of "grids": its outline in plan, at its height."""
    corners = [obj.matrix_world @ Vector(c) for c in obj.bound_box]
    xs, ys, zs = ([c[i] for c in corners] for i in range(3))
    size = max(max(xs) - min(xs), max(ys) - min(ys))
    if not size > 0:
        raise DesignError("work plane '%s' has no area in plan. Use a horizontal Plane object for it." % obj.name)
    if max(zs) - min(zs) > FLAT * size:
        raise DesignError("work plane '%s' is not horizontal (its height varies by %.3g). Use a flat, horizontal "
                          "Plane object for it." % (obj.name, max(zs) - min(zs)))
    settings = obj.dynrad_plane
    grid = {"name": file_name(obj.name), "rectangle": [min(xs), min(ys), max(xs), max(ys)],
            "height": (max(zs) + min(zs)) / 2}
    if settings.spacing > 0:
        grid["spacing"] = settings.spacing
    if settings.border > 0:
        grid["border"] = settings.border
    target = {}
    if settings.target_eavg > 0:
        target["Eavg"] = settings.target_eavg
    if settings.target_u0 > 0:
        target["U0"] = settings.target_u0
    if target:
        grid["target"] = target
    return grid


# ---------------------------------------------------------------------------
# The scene file


def build_scene(context):
    """(Model, scene dict without "meshes") for the visible objects; DesignError for
    anything dynrad cannot use, before anything is written."""
    meshes, lights, planes = design_objects(context)
    if not meshes:
        raise DesignError("there is no visible mesh to light. Show the room's objects (work planes are not lit).")
    model = Model()
    depsgraph = context.evaluated_depsgraph_get()
    for obj in meshes:
        model.add(obj, depsgraph)
    scene = {}
    luminaires = [luminaire_entry(o) for o in lights]
    if luminaires:
        scene["luminaires"] = luminaires
    sky = sky_entry(context.scene.dynrad_design)
    if sky:
        scene["sky"] = sky
    grids = [grid_entry(o) for o in planes]
    names = [g["name"] for g in grids]
    for name in names:
        if names.count(name) > 1:
            raise DesignError("two work planes are named '%s' in files. Rename one of them." % name)
    if grids:
        scene["grids"] = grids
    return model, scene


def write_scene(model, scene, folder):
    """Writes design.obj, design.mtl and design.json into `folder`; returns the JSON's path."""
    os.makedirs(folder, exist_ok=True)
    stem = os.path.join(folder, "design")
    document = {"meshes": [{"file": model.write(stem)}]}
    document.update(scene)
    with open(stem + ".json", "w") as f:
        json.dump(document, f, indent=2)
        f.write("\n")
    return stem + ".json"
