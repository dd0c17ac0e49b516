"""The add-on's lighting design, headless, against the command line.

Run by ctest as:
  blender -b --factory-startup --python tests/blender_design_test.py -- \
      ADDON_DIR LIBDYNRAD DYNRAD_EXE SAMPLES_DIR WORK_DIR

Builds a 4 x 4 x 3 m room in Blender, hangs a light object carrying the downlight
sample's IES file from its ceiling, lays a work plane at 0.8 m, and lights the design
with the add-on's operator. The operator writes design.json and the library solves it
through dynrad_scene_load: `dynrad solve` on that same file, with the same quality, must
give the same grid to the printed digit (one input, one pipeline, seeded sampling).
Then: the false-colour attribute covers every vertex, the HTML report names the grid
with its Eavg, a room open to an overcast sky and no luminaire is daylit, and bad input
(a missing IES file, a white material) stops the operator with a message naming the
object and adds nothing to the scene.
"""

import csv
import json
import math
import os
import subprocess
import sys
import traceback

import bmesh
import bpy

args = sys.argv[sys.argv.index("--") + 1:]
ADDON_DIR, LIBRARY, DYNRAD, SAMPLES, WORK = args
IES = os.path.join(SAMPLES, "downlight.ies")

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)


def material(name, base):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    m.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (base, base, base, 1)
    return m


def room(name, with_ceiling, paint):
    """A 4 x 4 x 3 m box from (0, 0, 0), faces turned inwards; without a ceiling, open to the sky."""
    mesh = bpy.data.meshes.new(name)
    b = bmesh.new()
    bmesh.ops.create_cube(b, size=1.0)
    bmesh.ops.scale(b, vec=(4, 4, 3), verts=b.verts)
    bmesh.ops.translate(b, vec=(2, 2, 1.5), verts=b.verts)
    if not with_ceiling:
        bmesh.ops.delete(b, geom=[f for f in b.faces if f.calc_center_median().z > 2.99], context="FACES_ONLY")
    bmesh.ops.reverse_faces(b, faces=b.faces)
    b.to_mesh(mesh)
    b.free()
    mesh.materials.append(paint)
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def run_operator():
    outcome = bpy.ops.scene.dynrad_light_design()
    check(outcome == {"FINISHED"}, "operator returned %s" % outcome)


def cli_solve(scene_file, stem):
    """`dynrad solve` on the add-on's scene file: (its report, its grid's points inside solids left out)."""
    report = stem + "_report.json"
    subprocess.run([DYNRAD, "solve", scene_file, "-o", stem + ".ply", "--quality", "draft", "--report", report, "-q"],
                   check=True)
    with open(report) as f:
        grids = json.load(f)["grids"]
    with open(stem + "_grid_work.csv") as f:
        points = [row for row in csv.DictReader(f) if row["masked"] == "0"]
    return grids, points


def expect_refusal(words, what):
    """The operator fails, its message holds every one of `words`, and the scene is as it was."""
    before = sorted(o.name for o in bpy.data.objects)
    try:
        bpy.ops.scene.dynrad_light_design()
        check(False, "%s: the operator did not fail" % what)
    except RuntimeError as error:
        message = str(error)
        for word in words:
            check(word in message, "%s: the message '%s' does not mention '%s'" % (what, message, word))
    check(sorted(o.name for o in bpy.data.objects) == before, "%s: the scene changed" % what)


def main():
    os.environ["DYNRAD_LIBRARY"] = LIBRARY
    sys.path.insert(0, ADDON_DIR)
    import dynrad_blender

    dynrad_blender.register()
    check(hasattr(bpy.ops.scene, "dynrad_light_design"), "the design operator is not registered")
    for obj in list(bpy.data.objects):  # the factory cube, camera and light
        bpy.data.objects.remove(obj)

    paint = material("paint", 0.6)
    closed = room("room", True, paint)
    open_room = room("courtyard", False, paint)
    open_room.hide_set(True)

    light = bpy.data.objects.new("Downlight", bpy.data.lights.new("Downlight", "POINT"))
    light.location = (2, 2, 2.9)
    light.data.dynrad.photometry = IES
    bpy.context.scene.collection.objects.link(light)

    bpy.ops.mesh.primitive_plane_add(size=4, location=(2, 2, 0.8))
    plane = bpy.context.active_object
    plane.name = "work"
    plane.dynrad_plane.is_work_plane = True
    plane.dynrad_plane.spacing = 0.5
    plane.dynrad_plane.border = 0.5

    bpy.context.scene.dynrad.quality = "draft"
    design = bpy.context.scene.dynrad_design
    design.folder = os.path.join(WORK, "scene")
    design.report_path = os.path.join(WORK, "report.html")
    if os.path.exists(design.report_path):
        os.remove(design.report_path)

    # 1. The luminaire: the same grid as `dynrad solve` on the same file.
    run_operator()
    lit = bpy.data.objects.get("Scene_dynrad")
    check(lit is not None and lit.get("dynrad_result"), "no result object 'Scene_dynrad'")
    scene_file = lit["dynrad_scene_file"]
    with open(scene_file) as f:
        written = json.load(f)
    check([g["name"] for g in written.get("grids", [])] == ["work"], "grids written: %s" % written.get("grids"))
    check(written["luminaires"][0]["photometry"] == IES and written["luminaires"][0]["aim"] == [0, 0, -1],
          "luminaire written: %s" % written["luminaires"])
    mesh = lit.data
    lux = mesh.attributes.get("illuminance")
    false = mesh.color_attributes.get("false_colour")
    n = len(mesh.vertices)
    check(lux is not None and lux.domain == "POINT" and lux.data_type == "FLOAT" and len(lux.data) == n > 0,
          "no POINT FLOAT 'illuminance' over the %d vertices" % n)
    check(false is not None and false.domain == "POINT" and false.data_type == "BYTE_COLOR" and len(false.data) == n,
          "no POINT BYTE_COLOR 'false_colour' over the %d vertices" % n)
    check(mesh.color_attributes.active_color_name == "false_colour", "the false colours are not active")
    check(lit["dynrad_unit"] == "lx" and lit["dynrad_scale_max"] > 0, "scale %s %s" % (
        lit.get("dynrad_scale_max"), lit.get("dynrad_unit")))
    grid = bpy.data.objects.get("work_grid")
    check(grid is not None, "no grid object 'work_grid'")
    cli_grids, cli_points = cli_solve(scene_file, os.path.join(WORK, "cli"))
    values = [0.0] * len(grid.data.vertices)
    grid.data.attributes["illuminance"].data.foreach_get("value", values)
    cli_eavg = cli_grids[0]["Eavg"]
    check(len(values) == len(cli_points) > 0, "%d grid points, dynrad solve has %d" % (len(values), len(cli_points)))
    check("%.6g" % grid["dynrad_Eavg"] == "%.6g" % cli_eavg,
          "Eavg %.9g lx, dynrad solve's %.9g lx" % (grid["dynrad_Eavg"], cli_eavg))
    mean = sum(values) / max(len(values), 1)  # 32-bit floats in the attribute
    check(abs(mean - cli_eavg) <= 1e-6 * cli_eavg, "mean of the points %.9g lx, Eavg %.9g lx" % (mean, cli_eavg))
    check(cli_eavg > 50, "the work plane under a 3000 lm downlight has %.3g lx" % cli_eavg)
    top = lit["dynrad_scale_max"]
    check(top >= max(values) and top <= 2.5 * max(values), "scale top %g for a brightest point %g" % (top, max(values)))
    check(os.path.isfile(design.report_path), "no report at %s" % design.report_path)
    if os.path.isfile(design.report_path):
        with open(design.report_path) as f:
            page = f.read()
        check("<td>work</td>" in page, "the report does not name the grid")
        check("<td class=\"n\">%.1f</td>" % cli_eavg in page, "the report has no Eavg %.1f" % cli_eavg)
        check("<td>Downlight</td>" in page, "the report does not list the light")
    print("design: %d vertices, %d grid points, Eavg %.4g lx (dynrad solve %.4g lx), scale 0 to %g lx" % (
        n, len(values), grid["dynrad_Eavg"], cli_eavg, top))

    # 2. Daylight alone: the room open to an overcast sky, the luminaire off.
    light.data.dynrad.enabled = False
    closed.hide_set(True)
    open_room.hide_set(False)
    design.sky = "cie_overcast"
    design.report_path = ""
    run_operator()
    grid = bpy.data.objects.get("work_grid")
    check(len([o for o in bpy.data.objects if o.name.startswith("work_grid")]) == 1, "the old grid was not replaced")
    eavg = grid.get("dynrad_Eavg", 0.0) if grid else 0.0
    check(0 < eavg < 10000, "daylight on the work plane: Eavg %g lx under a 10000 lx sky" % eavg)
    print("daylight: Eavg %.4g lx" % eavg)

    # 3. Bad input: the light's file is missing; then a white material.
    design.sky = "none"
    closed.hide_set(False)
    open_room.hide_set(True)
    light.data.dynrad.enabled = True
    missing = os.path.join(WORK, "missing.ies")
    light.data.dynrad.photometry = missing
    expect_refusal(["Downlight", missing, "does not exist"], "a missing IES file")
    light.data.dynrad.photometry = IES
    paint.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (1, 1, 1, 1)
    expect_refusal(["room", "paint", "reflectance", "below 1"], "a white material")


try:
    main()
except Exception:
    traceback.print_exc()
    failures.append("exception")
if failures:
    print("blender_design_test: %d checks failed" % len(failures))
    sys.stdout.flush()
    os._exit(1)
print("blender_design_test: all checks passed")
sys.stdout.flush()
os._exit(0)
