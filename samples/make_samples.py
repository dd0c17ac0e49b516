#!/usr/bin/env python3
"""Generate the sample scenes (OBJ + MTL) in this directory.

Writes, next to this script:
  cornell_box.obj/.mtl               measured Cornell box (millimetres, y up)
  globillum_room.obj/.mtl            1990 comparison room, 10 x 6 x 3 m, z up
  globillum_room_obstructed.obj      the same room with two partitions
  paper_sphere_room.obj              6 x 6 x 3 m room, sphere, two lamps
  paper_empty_room_small_source.obj  empty room, one small wall source
  paper_empty_room_front_wall.obj    empty room, whole front wall emits
  paper_rooms.mtl                    materials of the three paper_* scenes

The generated files are committed to the repository, so users do not need to
run this script; it is kept so the scenes can be checked and regenerated.
Standard library only; the output is deterministic.

Faces are untriangulated polygons, front side counter-clockwise; rooms face
inward, solids outward; meshes are conforming (no T-junctions).  Kd is diffuse
reflectance, Ke radiant exitance in W/m^2.  All of this is asserted.
"""

import itertools
import math
import os

OUT_DIR = os.path.dirname(os.path.abspath(__file__))
EPS = 1e-9


# ---------------------------------------------------------------- vectors ---
def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0])


def unit(a):
    length = math.sqrt(dot(a, a))
    return tuple(x / length for x in a)


def centroid(points):
    return tuple(sum(c) / len(points) for c in zip(*points))


def newell_normal(points):
    """Area-weighted normal of a polygon (robust with collinear vertices)."""
    n = [0.0, 0.0, 0.0]
    for a, b in zip(points, points[1:] + points[:1]):
        n[0] += (a[1] - b[1]) * (a[2] + b[2])
        n[1] += (a[2] - b[2]) * (a[0] + b[0])
        n[2] += (a[0] - b[0]) * (a[1] + b[1])
    return tuple(n)


def fmt(value):
    """Short, exact-looking decimal: 552.8, 0.75, 3, -0.525731."""
    text = f"{value:.6f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


# ------------------------------------------------------------------- mesh ---
class Mesh:
    """Indexed polygon mesh with groups and materials."""

    def __init__(self, title, mtllib, emitters):
        self.title = title          # header comment lines
        self.mtllib = mtllib
        self.emitters = set(emitters)
        self.points = []
        self.index = {}
        self.faces = []             # (group, material, [vertex indices])

    def vertex(self, p):
        """Index of point p; points are deduplicated by written coordinates."""
        key = tuple(fmt(c) for c in p)
        if key not in self.index:
            self.index[key] = len(self.points)
            self.points.append(tuple(float(c) for c in key))
        return self.index[key]

    def face(self, group, material, loop, expect, min_cos=0.999):
        """Add a polygon and assert its front side faces direction `expect`."""
        ids = [self.vertex(p) for p in loop]
        pts = [self.points[i] for i in ids]
        assert len(set(ids)) == len(ids) >= 3, (group, loop)
        n = unit(newell_normal(pts))
        assert dot(n, unit(expect)) > min_cos, f"{group}: {n} not {expect}"
        # The simple rule (v1-v0) x (v2-v0) must agree with the true normal.
        simple = cross(sub(pts[1], pts[0]), sub(pts[2], pts[0]))
        assert dot(simple, n) > EPS, f"{group}: bad first three vertices"
        self.faces.append((group, material, ids))

    # -- checks --------------------------------------------------------------
    def edges(self):
        for _, _, ids in self.faces:
            for a, b in zip(ids, ids[1:] + ids[:1]):
                yield a, b

    def check_conforming(self):
        """No vertex may lie strictly inside any polygon edge (T-junction)."""
        for a, b in {tuple(sorted(e)) for e in self.edges()}:
            pa, pb = self.points[a], self.points[b]
            length = math.dist(pa, pb)
            for i, p in enumerate(self.points):
                detour = math.dist(pa, p) + math.dist(p, pb)
                assert i in (a, b) or detour > length * (1 + 1e-9), \
                    f"T-junction: vertex {p} on edge {pa}-{pb}"

    def check_edges(self, closed):
        """Each directed edge is used once; closed meshes pair every edge
        with its reverse (watertight and consistently oriented)."""
        count = {}
        for e in self.edges():
            count[e] = count.get(e, 0) + 1
        assert all(c == 1 for c in count.values()), "directed edge repeated"
        if closed:
            missing = [e for e in count if (e[1], e[0]) not in count]
            assert not missing, f"open edges, e.g. {missing[:3]}"

    # -- output --------------------------------------------------------------
    def write(self, filename, closed):
        self.check_conforming()
        self.check_edges(closed)
        lines = [f"# {line}" for line in self.title]
        lines += [f"mtllib {self.mtllib}", ""]
        lines += ["v " + " ".join(fmt(c) for c in p) for p in self.points]
        current = None
        for group, material, ids in self.faces:
            if (group, material) != current:
                lines += ["", f"g {group}", f"usemtl {material}"]
                current = (group, material)
            lines.append("f " + " ".join(str(i + 1) for i in ids))
        with open(os.path.join(OUT_DIR, filename), "w", newline="\n") as f:
            f.write("\n".join(lines) + "\n")
        emitting = sum(1 for _, m, _ in self.faces if m in self.emitters)
        triangles = sum(len(ids) - 2 for _, _, ids in self.faces)
        print(f"{filename}: {len(self.points)} vertices, {len(self.faces)} "
              f"faces ({triangles} triangles), {emitting} emitting")


def write_mtl(filename, title, materials):
    """materials: list of (name, Kd triple, Ke triple or None)."""
    lines = [f"# {line}" for line in title]
    for name, kd, ke in materials:
        assert all(0 <= c < 1 for c in kd), name
        lines += ["", f"newmtl {name}", "Kd " + " ".join(fmt(c) for c in kd)]
        if ke:
            lines.append("Ke " + " ".join(fmt(round(c, 4)) for c in ke))
    with open(os.path.join(OUT_DIR, filename), "w", newline="\n") as f:
        f.write("\n".join(lines) + "\n")
    print(f"{filename}: {len(materials)} materials")


# ------------------------------------------------------------ Cornell box ---
def cornell_box():
    mesh = Mesh(["Cornell box; units: millimetres, y up; source: Cornell "
                 "University Program of Computer Graphics measured data.",
                 "Front (z = 0) is open. Light Ke = pi x published radiance."],
                "cornell_box.mtl", ["light"])
    up, down = (0, 1, 0), (0, -1, 0)
    y = 548.8
    mesh.face("floor", "white", [(552.8, 0, 0), (0, 0, 0), (0, 0, 559.2),
                                 (549.6, 0, 559.2)], up)
    # Light in the ceiling plane; the ceiling is cut into four pieces whose
    # boundaries pass through the light's corners (x 213..343, z 227..332).
    mesh.face("light", "light", [(343, y, 227), (343, y, 332), (213, y, 332),
                                 (213, y, 227)], down)
    ceiling = [
        [(556, y, 0), (556, y, 227), (343, y, 227), (213, y, 227),
         (0, y, 227), (0, y, 0)],
        [(556, y, 332), (556, y, 559.2), (0, y, 559.2), (0, y, 332),
         (213, y, 332), (343, y, 332)],
        [(556, y, 227), (556, y, 332), (343, y, 332), (343, y, 227)],
        [(213, y, 227), (213, y, 332), (0, y, 332), (0, y, 227)],
    ]
    for piece in ceiling:
        mesh.face("ceiling", "white", piece, down)
    mesh.face("back_wall", "white", [(549.6, 0, 559.2), (0, 0, 559.2),
                                     (0, y, 559.2), (556, y, 559.2)],
              (0, 0, -1))
    # The side walls' top edges carry the ceiling cut points (z 227, 332).
    mesh.face("green_wall", "green", [(0, 0, 559.2), (0, 0, 0), (0, y, 0),
                                      (0, y, 227), (0, y, 332),
                                      (0, y, 559.2)], (1, 0, 0))
    mesh.face("red_wall", "red", [(552.8, 0, 0), (549.6, 0, 559.2),
                                  (556, y, 559.2), (556, y, 332),
                                  (556, y, 227), (556, y, 0)],
              (-1, 0, 0), min_cos=0.99)
    blocks = [("short_block", 165, [(130, 65), (82, 225), (240, 272),
                                    (290, 114)]),
              ("tall_block", 330, [(423, 247), (265, 296), (314, 456),
                                   (472, 406)])]
    for name, h, footprint in blocks:
        mesh.face(name, "white", [(x, h, z) for x, z in footprint], up)
        cx, _, cz = centroid([(x, 0, z) for x, z in footprint])
        ring = footprint[1:] + footprint[:1]
        for (ax, az), (bx, bz) in zip(footprint, ring):
            away = ((ax + bx) / 2 - cx, 0, (az + bz) / 2 - cz)
            mesh.face(name, "white", [(ax, 0, az), (bx, 0, bz), (bx, h, bz),
                                      (ax, h, az)], away, min_cos=0)
    mesh.write("cornell_box.obj", closed=False)
    write_mtl("cornell_box.mtl",
              ["Cornell box materials (Cornell University Program of Computer "
               "Graphics data).",
               "Kd = diffuse reflectance; Ke = radiant exitance in W/m^2 "
               "(pi x radiance 17, 12, 4)."],
              [("white", (0.725, 0.71, 0.68), None),
               ("red", (0.63, 0.065, 0.05), None),
               ("green", (0.14, 0.45, 0.091), None),
               ("light", (0.78, 0.78, 0.78),
                tuple(math.pi * c for c in (17, 12, 4)))])


# ------------------------------------------------- axis-aligned grid rooms ---
def axis_rect(axis, value, sign, u_range, v_range):
    """Rectangle in the plane coord[axis] == value whose front faces
    sign * axis.  u, v are the next two axes in cyclic order (u x v = axis)."""
    i, j = (axis + 1) % 3, (axis + 2) % 3
    loop = []
    for u, v in ((0, 0), (1, 0), (1, 1), (0, 1)):
        p = [value] * 3
        p[i], p[j] = u_range[u], v_range[v]
        loop.append(tuple(p))
    return loop if sign > 0 else loop[::-1]


def grid_face(mesh, axis, value, sign, box, cuts, role):
    """Cut the face of `box` (per-axis (lo, hi)) lying at coord[axis] == value
    into rectangles at every cut coordinate inside it.  role(centre) gives
    (group, material) for a cell, or None to omit the cell."""
    i, j = (axis + 1) % 3, (axis + 2) % 3
    expect = tuple(sign if k == axis else 0 for k in range(3))

    def spans(k):
        lo, hi = box[k]
        ticks = sorted({lo, hi} | {c for c in cuts[k] if lo < c < hi})
        return list(zip(ticks, ticks[1:]))

    for u_range in spans(i):
        for v_range in spans(j):
            loop = axis_rect(axis, value, sign, u_range, v_range)
            assigned = role(centroid(loop))
            if assigned:
                mesh.face(assigned[0], assigned[1], loop, expect)


def room(mesh, size, cuts, names, role):
    """Six inward-facing room faces.  names maps floor, ceiling, x0, x1, y0,
    y1 to group names; role(name, centre, default) returns a cell's
    (group, material), normally `default`, or None to omit the cell."""
    box = [(0.0, s) for s in size]
    defaults = {"floor": "floor", "ceiling": "ceiling"}
    for key, axis, value, sign in [
            ("floor", 2, 0.0, 1), ("ceiling", 2, size[2], -1),
            ("y0", 1, 0.0, 1), ("y1", 1, size[1], -1),
            ("x0", 0, 0.0, 1), ("x1", 0, size[0], -1)]:
        name = names[key]
        plain = (name, defaults.get(key, "wall"))
        grid_face(mesh, axis, value, sign, box, cuts,
                  lambda c, name=name, plain=plain: role(name, c, plain))


def inside(p, box):
    return all(lo - EPS <= p[k] <= hi + EPS for k, (lo, hi) in enumerate(box))


GLOBILLUM_NAMES = {"floor": "floor", "ceiling": "ceiling", "y0": "wall_y0",
                   "y1": "wall_y6", "x0": "wall_x0", "x1": "wall_x10"}
GLOBILLUM_LIGHT = [(4.75, 5.25), (2.75, 3.25), (3.0, 3.0)]


def globillum_room(obstructed):
    partitions = []
    if obstructed:
        # (group, box, faces as (axis, value, sign)): sides and free end only.
        partitions = [
            ("partition_a", [(2.95, 3.05), (3.0, 6.0), (0.0, 3.0)],
             [(0, 2.95, -1), (0, 3.05, 1), (1, 3.0, -1)]),
            ("partition_b", [(6.95, 7.05), (0.0, 3.0), (0.0, 3.0)],
             [(0, 6.95, -1), (0, 7.05, 1), (1, 3.0, 1)]),
        ]
        cuts = ([0, 2.95, 3.05, 4.75, 5.25, 6.95, 7.05, 10],
                [0, 2.75, 3, 3.25, 6], [0, 3])
        filename = "globillum_room_obstructed.obj"
        what = "with two full-height partitions 0.1 m thick"
    else:
        cuts = ([0, 4.75, 5.25, 10], [0, 2.75, 3.25, 6], [0, 3])
        filename = "globillum_room.obj"
        what = "empty"
    mesh = Mesh([f"Global illumination comparison room, {what}; units: "
                 "metres, z up; source: Ward, Rushmeier et al. (1990).",
                 "Room 10 x 6 x 3 with the origin at a corner; 0.5 x 0.5 m "
                 "source in the middle of the ceiling."],
                "globillum_room.mtl", ["light"])

    def role(name, c, plain):
        if any(inside(c, box) for _, box, _ in partitions):
            return None                     # hidden under a partition
        if name == "ceiling" and inside(c, GLOBILLUM_LIGHT):
            return ("light", "light")
        return plain

    room(mesh, (10.0, 6.0, 3.0), cuts, GLOBILLUM_NAMES, role)
    for group, box, faces in partitions:
        for axis, value, sign in faces:
            grid_face(mesh, axis, value, sign, box, cuts,
                      lambda c, g=group: (g, "wall"))
    mesh.write(filename, closed=True)


# ------------------------------------------------------ paper test scenes ---
PAPER_SIZE = (6.0, 6.0, 3.0)
PAPER_DIV = 8
PAPER_NAMES = {"floor": "floor", "ceiling": "ceiling", "y0": "front_wall",
               "y1": "back_wall", "x0": "left_wall", "x1": "right_wall"}


def front_cell(c):
    """(column along x, row along z) of a front-wall grid cell centre."""
    return (int(c[0] / (PAPER_SIZE[0] / PAPER_DIV)),
            int(c[2] / (PAPER_SIZE[2] / PAPER_DIV)))


def icosphere(centre, radius):
    """Icosahedron subdivided once (80 triangles), projected on the sphere,
    every triangle facing outward."""
    phi = (1 + math.sqrt(5)) / 2
    verts = []
    for a, b in itertools.product((-1, 1), repeat=2):
        verts += [(a, b * phi, 0), (0, a, b * phi), (b * phi, 0, a)]
    verts = [unit(v) for v in verts]
    edge = min(math.dist(p, q) for p, q in itertools.combinations(verts, 2))
    # The 20 faces are exactly the vertex triples at mutual edge distance.
    tris = [[verts[i] for i in t]
            for t in itertools.combinations(range(12), 3)
            if all(abs(math.dist(verts[p], verts[q]) - edge) < 1e-9
                   for p, q in itertools.combinations(t, 2))]
    assert len(tris) == 20
    fine = []
    for a, b, c in tris:
        ab, bc, ca = (unit(tuple((p[k] + q[k]) / 2 for k in range(3)))
                      for p, q in ((a, b), (b, c), (c, a)))
        fine += [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
    out = []
    for tri in fine:
        if dot(newell_normal(tri), centroid(tri)) < 0:
            tri = tri[::-1]
        out.append([tuple(centre[k] + radius * p[k] for k in range(3))
                    for p in tri])
    return out


def paper_room(variant):
    cuts = tuple([s * k / PAPER_DIV for k in range(PAPER_DIV + 1)]
                 for s in PAPER_SIZE)
    if variant == "sphere":
        filename, emitters = "paper_sphere_room.obj", ["lamp"]
        what = ("sphere (centre 3, 3.5, 1; radius 0.8) lit by two lamps "
                "high on the front wall, left and right")
        # Left/right as seen from the front wall looking into the room (+y).
        lights = {(1, 6): ("light_left", "lamp"),
                  (6, 6): ("light_right", "lamp")}
    elif variant == "small":
        filename = "paper_empty_room_small_source.obj"
        emitters = ["small_source"]
        what = "empty room, one front-wall grid cell (column 3, row 6) emits"
        lights = {(3, 6): ("light", "small_source")}
    else:
        filename = "paper_empty_room_front_wall.obj"
        emitters = ["front_wall_source"]
        what = "empty room, the whole front wall emits"
        lights = {cell: ("front_wall", "front_wall_source")
                  for cell in itertools.product(range(PAPER_DIV), repeat=2)}
    mesh = Mesh([f"Test scene, {what}; units: metres, z up; source: Dubuis "
                 "& Bieri's paper (sizes and tessellation are our choice).",
                 "Room 6 x 6 x 3: x across, y depth, front wall y = 0; "
                 "every room face is an 8 x 8 grid of quads."],
                "paper_rooms.mtl", emitters)

    def role(name, c, plain):
        return lights.get(front_cell(c), plain) if name == "front_wall" \
            else plain

    room(mesh, PAPER_SIZE, cuts, PAPER_NAMES, role)
    if variant == "sphere":
        centre = (3.0, 3.5, 1.0)
        for tri in icosphere(centre, 0.8):
            mesh.face("sphere", "sphere", tri, sub(centroid(tri), centre),
                      min_cos=0.95)
    mesh.write(filename, closed=True)   # room and sphere are each closed


def main():
    cornell_box()
    globillum_room(obstructed=False)
    globillum_room(obstructed=True)
    write_mtl("globillum_room.mtl",
              ["Materials of the 1990 comparison room "
               "(Ward, Rushmeier et al.).",
               "Kd = diffuse reflectance; Ke = radiant exitance in W/m^2."],
              [("floor", (0.3, 0.3, 0.3), None),
               ("ceiling", (0.7, 0.7, 0.7), None),
               ("wall", (0.5, 0.5, 0.5), None),
               ("light", (0, 0, 0), (31.416, 31.416, 31.416))])
    for variant in ("sphere", "small", "front"):
        paper_room(variant)
    write_mtl("paper_rooms.mtl",
              ["Materials of the paper_* scenes (Dubuis & Bieri test scenes).",
               "Kd = diffuse reflectance; Ke = radiant exitance in W/m^2."],
              [("floor", (0.3, 0.3, 0.3), None),
               ("ceiling", (0.7, 0.7, 0.7), None),
               ("wall", (0.5, 0.5, 0.5), None),
               ("sphere", (0.6, 0.35, 0.2), None),
               ("lamp", (0, 0, 0), (400, 400, 400)),
               ("small_source", (0, 0, 0), (640, 640, 640)),
               ("front_wall_source", (0, 0, 0), (10, 10, 10))])


if __name__ == "__main__":
    main()
