"""A design solve's result as Blender objects, all built before any is linked:

- the lit mesh (`<scene>_dynrad`) with point attributes `illuminance` (float, lx),
  `false_colour` (byte colour on the report's scale, active: Solid mode with Attribute
  colours shows it), `radiosity` (float colour) and `radiosity_display` (byte colour);
  its custom properties give the scale: dynrad_scale_min, dynrad_scale_max, dynrad_unit;
- per grid, a point cloud (`<grid>_grid`: a mesh of vertices only) with a float point
  attribute `illuminance` and the grid's figures as custom properties (Eavg, Emin, Emax,
  U0). Points inside solids are left out.

Each is tagged `dynrad_result`; the previous ones of the same name are replaced.
"""

import math

import bpy

from . import capi


def legend_top(peak):
    """A round number at or above `peak`: 1, 2, 2.5 or 5 times a power of ten."""
    if not peak > 0 or not math.isfinite(peak):
        return 1.0
    power = 10.0 ** math.floor(math.log10(peak))
    for step in (1, 2, 2.5, 5, 10):
        if step * power >= peak * (1 - 1e-12):
            return step * power
    return 10 * power


def percentile(values, fraction):
    ordered = sorted(v for v in values if math.isfinite(v))
    return ordered[min(len(ordered) - 1, int(fraction * len(ordered)))] if ordered else 0.0


def scale_top(result, requested):
    """The false colours' top: the user's, else above the grids' brightest point, else
    above the surfaces' 98th percentile (a luminaire's own face would wash it out)."""
    if requested > 0:
        return requested
    grid_peak = max((p for _, points in result.grids for p in points[3::4] if math.isfinite(p)), default=0.0)
    return legend_top(grid_peak if grid_peak > 0 else percentile(result.illuminance, 0.98))


def triangle_mesh(name, result):
    """A new Blender mesh holding the result's refined triangles (no attributes yet)."""
    mesh = bpy.data.meshes.new(name)
    n, t = result.vertex_count, result.triangle_count
    mesh.vertices.add(n)
    mesh.vertices.foreach_set("co", [float(x) for x in result.positions])
    mesh.loops.add(3 * t)
    mesh.loops.foreach_set("vertex_index", result.triangles)
    mesh.polygons.add(t)
    mesh.polygons.foreach_set("loop_start", range(0, 3 * t, 3))
    mesh.polygons.foreach_set("loop_total", [3] * t)
    return mesh


def radiosity_attributes(mesh, result):
    """Adds the colour attributes `radiosity` (linear, float) and `radiosity_display`
    (the command line's display bytes, sRGB) to the result's mesh."""
    rgba = [1.0] * (4 * result.vertex_count)
    linear = mesh.color_attributes.new("radiosity", "FLOAT_COLOR", "POINT")
    for c in range(3):
        rgba[c::4] = result.radiosity[c::3]
    linear.data.foreach_set("color", rgba)
    display = mesh.color_attributes.new("radiosity_display", "BYTE_COLOR", "POINT")
    for c in range(3):
        rgba[c::4] = [b / 255.0 for b in result.display[c::3]]
    display.data.foreach_set("color_srgb", rgba)  # the bytes as they are: already sRGB


def _lit_mesh(library, result, name, top, unit):
    mesh = triangle_mesh(name, result)
    n = result.vertex_count
    mesh.update()
    mesh.validate()

    lux = mesh.attributes.new("illuminance", "FLOAT", "POINT")
    lux.data.foreach_set("value", result.illuminance)
    # The report's scale, sampled once per byte step and looked up per vertex.
    table = [capi.false_colour(library, k / 255.0) for k in range(256)]
    rgba = [1.0] * (4 * n)
    for v, e in enumerate(result.illuminance):
        colour = table[max(0, min(255, int(round(255 * e / top))))]
        rgba[4 * v:4 * v + 3] = [c / 255.0 for c in colour]
    false = mesh.color_attributes.new("false_colour", "BYTE_COLOR", "POINT")
    false.data.foreach_set("color_srgb", rgba)  # the scale's bytes as they are: sRGB
    radiosity_attributes(mesh, result)
    # By name: adding attributes may move the earlier ones, leaving `false` stale.
    mesh.color_attributes.active_color = mesh.color_attributes["false_colour"]
    mesh.color_attributes.render_color_index = mesh.color_attributes.find("false_colour")
    obj = bpy.data.objects.new(name, mesh)
    obj["dynrad_scale_min"] = 0.0
    obj["dynrad_scale_max"] = top
    obj["dynrad_unit"] = unit
    return obj


def _grid_cloud(name, points, figures):
    inside = [k for k in range(len(points) // 4) if math.isfinite(points[4 * k + 3])]
    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(len(inside))
    mesh.vertices.foreach_set("co", [points[4 * k + c] for k in inside for c in range(3)])
    lux = mesh.attributes.new("illuminance", "FLOAT", "POINT")
    lux.data.foreach_set("value", [points[4 * k + 3] for k in inside])
    obj = bpy.data.objects.new(name, mesh)
    for key in ("Eavg", "Emin", "Emax", "U0"):
        if isinstance(figures.get(key), (int, float)):
            obj["dynrad_" + key] = float(figures[key])
    return obj


def add_result_objects(context, library, result, name, requested_top):
    """Builds every object, then replaces the previous ones and links them; returns
    (lit object, grid objects, top of the scale)."""
    unit = "lx" if result.report_json.get("units") == "photometric" else "W/m2"
    top = scale_top(result, requested_top)
    figures = {g.get("name"): g for g in result.report_json.get("grids", [])}
    names = [name] + [grid + "_grid" for grid, _ in result.grids]
    built = [_lit_mesh(library, result, name, top, unit)]
    built += [_grid_cloud(grid + "_grid", points, figures.get(grid, {})) for grid, points in result.grids]
    for obj, wanted in zip(built, names):  # the previous result of that name goes, with its mesh
        old = bpy.data.objects.get(wanted)
        if old is not None and old is not obj and old.get("dynrad_result"):
            old_mesh = old.data
            bpy.data.objects.remove(old)
            if old_mesh is not None and old_mesh.users == 0:
                bpy.data.meshes.remove(old_mesh)
        obj.name = wanted
    for obj in built:
        obj["dynrad_result"] = True
        context.scene.collection.objects.link(obj)
    return built[0], built[1:], top
