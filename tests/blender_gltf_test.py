"""A lit model through glTF into Blender, headless.

Run by ctest as:
  blender -b --factory-startup --python tests/blender_gltf_test.py -- DYNRAD_EXE SAMPLES_DIR WORK_DIR

Lights samples/cornell_box.obj with `dynrad solve` twice, to .ply and to .glb, then
imports the .glb with Blender's own glTF importer and checks that:
- the vertex and triangle counts are the PLY's (nothing merged, nothing lost);
- there is one object per group of the OBJ (the box's walls and blocks by name);
- every corner's colour in Blender is the COLOR_0 the file holds for a vertex at that
  position, to the byte Blender stores it in;
- the box stands: its floor is Blender's lowest surface (z up), as in the OBJ (y up);
- the custom attribute _RADIOSITY and the unlit materials are in the file.
The .glb is read here with struct (no glTF library), so the check does not share the
writer's code.
"""

import json
import os
import struct
import subprocess
import sys

import bpy

DYNRAD, SAMPLES, WORK = sys.argv[sys.argv.index("--") + 1:]
SAMPLE = os.path.join(SAMPLES, "cornell_box.obj")


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def solve(out, up):
    # The Cornell box is y up: read with --up y it stands on its floor in dynrad (z up)
    # and, written to glTF's y up, in Blender again.
    subprocess.run([DYNRAD, "solve", SAMPLE, "-o", out, "--quality", "draft", "-q", "--up", up], check=True)


def read_glb(path):
    data = open(path, "rb").read()
    magic, version, length = struct.unpack_from("<4sII", data, 0)
    if magic != b"glTF" or version != 2 or length != len(data):
        fail("not a glTF 2.0 binary: %r %d %d/%d" % (magic, version, length, len(data)))
    json_length, json_type = struct.unpack_from("<II", data, 12)
    if json_type != 0x4E4F534A:
        fail("first chunk is not JSON")
    doc = json.loads(data[20:20 + json_length])
    bin_at = 20 + json_length
    bin_length, bin_type = struct.unpack_from("<II", data, bin_at)
    if bin_type != 0x004E4942:
        fail("second chunk is not BIN")
    binary = data[bin_at + 8:bin_at + 8 + bin_length]

    def floats(accessor_index, width):
        a = doc["accessors"][accessor_index]
        view = doc["bufferViews"][a["bufferView"]]
        start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        values = struct.unpack_from("<%df" % (a["count"] * width), binary, start)
        return [values[i * width:(i + 1) * width] for i in range(a["count"])]

    return doc, floats


def ply_vertex_count(path):
    with open(path, "rb") as f:
        for line in f:
            if line.startswith(b"element vertex"):
                return int(line.split()[2])
    fail("no vertex count in " + path)


def linear_to_byte(c):
    s = c * 12.92 if c <= 0.0031308 else 1.055 * c ** (1 / 2.4) - 0.055
    return round(max(0.0, min(1.0, s)) * 255)


def main():
    ply, glb = os.path.join(WORK, "cornell.ply"), os.path.join(WORK, "cornell.glb")
    solve(ply, "y")
    solve(glb, "y")
    doc, floats = read_glb(glb)
    attributes = doc["meshes"][0]["primitives"][0]["attributes"]
    for name in ("POSITION", "COLOR_0", "_RADIOSITY"):
        if name not in attributes:
            fail("attribute %s missing: %s" % (name, sorted(attributes)))
    if "KHR_materials_unlit" not in doc.get("extensionsUsed", []):
        fail("materials are not unlit")
    positions = floats(attributes["POSITION"], 3)
    colours = floats(attributes["COLOR_0"], 3)
    vertices = ply_vertex_count(ply)
    if len(positions) != vertices:
        fail("the .glb holds %d vertices, the .ply %d" % (len(positions), vertices))
    at = {}
    for p, c in zip(positions, colours):
        at.setdefault(tuple(round(x, 4) for x in p), []).append(tuple(linear_to_byte(x) for x in c))

    bpy.ops.wm.read_factory_settings(use_empty=True)
    # SMOOTH shading: Debian's Blender 3.4 with NumPy 1.24 fails in the importer's
    # NORMALS path (np.bool); the file has no normals for it to read anyway.
    bpy.ops.import_scene.gltf(filepath=glb, import_shading="SMOOTH")
    objects = [o for o in bpy.data.objects if o.type == "MESH"]
    names = sorted(o.name for o in objects)
    expected = ["back_wall", "ceiling", "floor", "green_wall", "light", "red_wall", "short_block", "tall_block"]
    if names != expected:
        fail("objects %s, expected the OBJ's groups %s" % (names, expected))
    total_vertices = sum(len(o.data.vertices) for o in objects)
    total_triangles = sum(len(o.data.polygons) for o in objects)
    if total_vertices != vertices:
        fail("Blender has %d vertices, the .ply %d" % (total_vertices, vertices))
    corners = mismatched = 0
    worst = 0
    for o in objects:
        mesh = o.data
        colour = mesh.color_attributes[0]
        for loop in mesh.loops:
            co = o.matrix_world @ mesh.vertices[loop.vertex_index].co
            key = tuple(round(x, 4) for x in (co[0], co[2], -co[1]))  # Blender's z up back to the file's y up
            seen = tuple(linear_to_byte(x) for x in colour.data[loop.index].color[:3])
            candidates = at.get(key)
            corners += 1
            if not candidates:
                mismatched += 1
                continue
            best = min(max(abs(a - b) for a, b in zip(seen, c)) for c in candidates)
            worst = max(worst, best)
            if best > 1:
                mismatched += 1
    floor = [o for o in objects if o.name == "floor"][0]
    lowest = min((o.matrix_world @ v.co)[2] for o in objects for v in o.data.vertices)
    floor_top = max((floor.matrix_world @ v.co)[2] for v in floor.data.vertices)
    if floor_top - lowest > 1e-3 * 550:
        fail("the floor is not at the bottom: floor up to z %.3f, lowest point %.3f" % (floor_top, lowest))
    print("glTF round trip: %d objects, %d vertices, %d triangles, %d corners, %d mismatched, worst %d/255"
          % (len(objects), total_vertices, total_triangles, corners, mismatched, worst))
    if mismatched:
        fail("%d of %d corners differ from the file's colours by more than 1/255" % (mismatched, corners))


try:
    main()
except SystemExit:
    raise
except Exception as e:  # anything else fails the test too
    fail(repr(e))
sys.exit(0)
