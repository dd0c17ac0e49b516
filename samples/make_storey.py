#!/usr/bin/env python3
"""Generates one storey of a house built the way IFC exports are: every element a
closed, triangulated solid, nothing imprinted on anything else.

    samples/make_storey.py [OUT.obj]      (default: samples/storey.obj beside this script)

Writes OUT.obj, OUT.mtl and OUT_layout.json (the rooms' inner rectangles and the
furniture footprints, for benchmarks and tests that sample the floor near the walls).

What makes it like an export (and hard for a radiosity mesh):
- a floor slab (0.25 m) and a ceiling slab run under and over all walls;
- the outer walls (0.3 m) run from the bottom of the floor slab to the top of the
  ceiling slab, so they pass through both, and overlap each other at the corners;
- the inner walls (0.12 m) stand on the floor slab, touch the ceiling slab, and run
  into the outer walls up to their axes;
- window openings (no glass) in the outer walls, an entrance door, doors in the inner
  walls: walls with holes, triangulated;
- a bed with a headboard against a wall, a table on four legs, a cupboard against a
  wall, a sofa: closed boxes standing on the floor;
- a ceiling lamp per room: a closed housing fixed under the ceiling slab, its bottom
  face emitting.
Units metres, z up. The storey is 12 x 9 m (outer wall axes), ceiling height 2.7 m.
"""
import json
import os
import sys

SLAB = 0.25
HEIGHT = 2.7          # floor slab top (z = 0) to ceiling slab bottom
OUTER, INNER = 0.3, 0.12
SX, SY = 12.0, 9.0    # outer wall axes: x = 0 and SX, y = 0 and SY
XA, YA = 6.5, 5.0     # inner wall axes: one along y at x = XA, one along x at y = YA
DOOR_W, DOOR_H = 0.9, 2.1
WIN_W, WIN_H, SILL = 1.4, 1.3, 0.9

MATERIALS = [  # name, reflectance, emission (W/m2)
    ("floor", 0.35, 0), ("ceiling", 0.8, 0), ("plaster", 0.6, 0), ("wood", 0.4, 0),
    ("fabric", 0.5, 0), ("cupboard", 0.55, 0), ("housing", 0.7, 0), ("lamp", 0.0, 150),
]


class Obj:
    def __init__(self):
        self.v, self.index = [], {}
        self.groups = []  # (name, [(material, (i, j, k))])

    def vertex(self, p):
        key = tuple(round(c, 6) for c in p)
        if key not in self.index:
            self.index[key] = len(self.v) + 1
            self.v.append(key)
        return self.index[key]

    def element(self, name):
        self.groups.append((name, []))

    def quad(self, material, a, b, c, d):
        """Counter-clockwise seen from the front; written as two triangles (IFC exports
        are triangulated)."""
        ia, ib, ic, id_ = (self.vertex(p) for p in (a, b, c, d))
        faces = self.groups[-1][1]
        faces.append((material, (ia, ib, ic)))
        faces.append((material, (ia, ic, id_)))


def cuboid_solid(obj, lo, hi, material, bottom=None):
    """A closed box facing outward; `bottom` overrides the material of the -z face."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    p = lambda i, j, k: ((x0, x1)[i], (y0, y1)[j], (z0, z1)[k])
    obj.quad(material, p(0, 0, 1), p(1, 0, 1), p(1, 1, 1), p(0, 1, 1))  # +z
    obj.quad(bottom or material, p(0, 0, 0), p(0, 1, 0), p(1, 1, 0), p(1, 0, 0))  # -z
    obj.quad(material, p(0, 0, 0), p(1, 0, 0), p(1, 0, 1), p(0, 0, 1))  # -y
    obj.quad(material, p(1, 1, 0), p(0, 1, 0), p(0, 1, 1), p(1, 1, 1))  # +y
    obj.quad(material, p(0, 1, 0), p(0, 0, 0), p(0, 0, 1), p(0, 1, 1))  # -x
    obj.quad(material, p(1, 0, 0), p(1, 1, 0), p(1, 1, 1), p(1, 0, 1))  # +x


def wall_solid(obj, start, axis, length, thickness, z0, z1, openings, material="plaster"):
    """A wall along `axis` ('x' or 'y') from `start` (a point on its axis line), with
    rectangular openings (s0, s1, zb, zt) through it: the box minus the openings, as a
    closed solid. The wall is cut into cells on a grid through the openings' edges;
    faces are the cells' sides between solid and empty."""
    ss = sorted({0.0, length} | {o[0] for o in openings} | {o[1] for o in openings})
    zs = sorted({z0, z1} | {o[2] for o in openings} | {o[3] for o in openings})
    ns, nz = len(ss) - 1, len(zs) - 1

    def solid(i, j):
        if i < 0 or j < 0 or i >= ns or j >= nz:
            return False
        sm, zm = (ss[i] + ss[i + 1]) / 2, (zs[j] + zs[j + 1]) / 2
        return not any(o[0] < sm < o[1] and o[2] < zm < o[3] for o in openings)

    h = thickness / 2

    def w(s, t, z):  # wall coordinates (along, across, up) to world
        if axis == 'x':
            return (start[0] + s, start[1] + t, z)
        return (start[0] - t, start[1] + s, z)  # along +y, across towards -x

    for i in range(ns):
        for j in range(nz):
            if not solid(i, j):
                continue
            sa, sb, za, zb = ss[i], ss[i + 1], zs[j], zs[j + 1]
            obj.quad(material, w(sa, -h, za), w(sb, -h, za), w(sb, -h, zb), w(sa, -h, zb))  # -t side
            obj.quad(material, w(sb, h, za), w(sa, h, za), w(sa, h, zb), w(sb, h, zb))      # +t side
            if not solid(i - 1, j):
                obj.quad(material, w(sa, h, za), w(sa, -h, za), w(sa, -h, zb), w(sa, h, zb))
            if not solid(i + 1, j):
                obj.quad(material, w(sb, -h, za), w(sb, h, za), w(sb, h, zb), w(sb, -h, zb))
            if not solid(i, j - 1):
                obj.quad(material, w(sa, -h, za), w(sa, h, za), w(sb, h, za), w(sb, -h, za))
            if not solid(i, j + 1):
                obj.quad(material, w(sa, h, zb), w(sa, -h, zb), w(sb, -h, zb), w(sb, h, zb))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "storey.obj")
    obj = Obj()
    ho, hi = OUTER / 2, INNER / 2
    windows = []  # the floor plan's window openings, as rectangles (for the layout)

    def window(s):
        return (s - WIN_W / 2, s + WIN_W / 2, SILL, SILL + WIN_H)

    def windows_x(y, centres):  # windows in an outer wall along x; s = x + ho
        for c in centres:
            windows.append([c - ho - WIN_W / 2, y - ho, c - ho + WIN_W / 2, y + ho])

    def windows_y(x, centres):
        for c in centres:
            windows.append([x - ho, c - ho - WIN_W / 2, x + ho, c - ho + WIN_W / 2])

    door = lambda s: (s - DOOR_W / 2, s + DOOR_W / 2, 0.0, DOOR_H)
    doors = []  # the floor plan's door openings, as rectangles

    def door_x(x, y, thickness):  # a door in a wall along x centred at x, for the layout
        doors.append([x - DOOR_W / 2, y - thickness / 2, x + DOOR_W / 2, y + thickness / 2])

    def door_y(x, y, thickness):
        doors.append([x - thickness / 2, y - DOOR_W / 2, x + thickness / 2, y + DOOR_W / 2])

    obj.element("IfcSlab_floor")
    cuboid_solid(obj, (-ho, -ho, -SLAB), (SX + ho, SY + ho, 0), "floor")
    obj.element("IfcSlab_ceiling")
    cuboid_solid(obj, (-ho, -ho, HEIGHT), (SX + ho, SY + ho, HEIGHT + SLAB), "ceiling")

    # Outer walls: through both slabs, each running over the corners (they overlap there).
    zb, zt = -SLAB, HEIGHT + SLAB
    obj.element("IfcWall_south")
    wall_solid(obj, (-ho, 0), 'x', SX + OUTER, OUTER, zb, zt,
               [window(ho + 2.5), window(ho + 9.0), (ho + 4.6, ho + 5.6, 0.0, DOOR_H)])
    windows_x(0, [ho + 2.5, ho + 9.0])
    obj.element("IfcWall_north")
    wall_solid(obj, (-ho, SY), 'x', SX + OUTER, OUTER, zb, zt, [window(ho + 2.5), window(ho + 9.5)])
    windows_x(SY, [ho + 2.5, ho + 9.5])
    obj.element("IfcWall_west")
    wall_solid(obj, (0, -ho), 'y', SY + OUTER, OUTER, zb, zt, [window(ho + 2.5), window(ho + 7.0)])
    windows_y(0, [ho + 2.5, ho + 7.0])
    obj.element("IfcWall_east")
    wall_solid(obj, (SX, -ho), 'y', SY + OUTER, OUTER, zb, zt, [window(ho + 2.5), window(ho + 7.0)])
    windows_y(SX, [ho + 2.5, ho + 7.0])
    # Inner walls: on the floor slab, under the ceiling slab, into the outer walls to
    # their axes (so their ends are inside the outer walls).
    obj.element("IfcWall_inner_x")
    wall_solid(obj, (0, YA), 'x', SX, INNER, 0, HEIGHT, [door(2.5), door(9.0)])
    door_x(2.5, YA, INNER)
    door_x(9.0, YA, INNER)
    obj.element("IfcWall_inner_y")
    wall_solid(obj, (XA, 0), 'y', YA, INNER, 0, HEIGHT, [door(2.5)])
    door_y(XA, 2.5, INNER)

    obj.element("IfcWall_inner_y2")
    wall_solid(obj, (SX / 2, YA), 'y', SY - YA, INNER, 0, HEIGHT, [door(1.2)])
    door_y(SX / 2, YA + 1.2, INNER)
    doors.append([4.6, -ho, 5.6, ho])  # the entrance

    # Rooms: the inner faces of their walls.
    rooms = {
        "living": (ho, ho, XA - hi, YA - hi),
        "kitchen": (XA + hi, ho, SX - ho, YA - hi),
        "bedroom": (ho, YA + hi, SX / 2 - hi, SY - ho),
        "study": (SX / 2 + hi, YA + hi, SX - ho, SY - ho),
    }

    furniture = []

    def furnish(name, lo, hi_, material):
        obj.element(name)
        cuboid_solid(obj, lo, hi_, material)
        furniture.append({"name": name, "rectangle": [lo[0], lo[1], hi_[0], hi_[1]], "height": hi_[2]})

    # Bed against the bedroom's north wall, headboard touching it.
    bx0, by1 = 3.5, SY - ho
    furnish("IfcFurniture_bed", (bx0, by1 - 2.1, 0), (bx0 + 1.6, by1 - 0.08, 0.5), "fabric")
    furnish("IfcFurniture_headboard", (bx0, by1 - 0.08, 0), (bx0 + 1.6, by1, 1.0), "wood")
    # Table on four legs in the living room.
    tx0, ty0, tx1, ty1, top = 2.2, 1.8, 3.8, 2.7, 0.72
    obj.element("IfcFurniture_table")
    cuboid_solid(obj, (tx0, ty0, top), (tx1, ty1, top + 0.04), "wood")
    for lx, ly in [(tx0, ty0), (tx1 - 0.06, ty0), (tx0, ty1 - 0.06), (tx1 - 0.06, ty1 - 0.06)]:
        cuboid_solid(obj, (lx, ly, 0), (lx + 0.06, ly + 0.06, top), "wood")
    furniture.append({"name": "IfcFurniture_table", "rectangle": [tx0, ty0, tx1, ty1], "height": top + 0.04})
    # Sofa in the living room, a cupboard against the kitchen's east wall.
    furnish("IfcFurniture_sofa", (1.2, 3.6, 0), (3.4, 4.4, 0.8), "fabric")
    furnish("IfcFurniture_cupboard", (SX - ho - 0.6, 3.4, 0), (SX - ho, 4.6, 2.0), "cupboard")
    # Study desk (a closed box) by the window.
    furnish("IfcFurniture_desk", (8.0, SY - ho - 0.7, 0), (9.6, SY - ho - 0.05, 0.75), "wood")

    # A lamp per room: housing fixed under the ceiling slab, its bottom emitting.
    lamps = []
    for name, (x0, y0, x1, y1) in rooms.items():
        cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
        obj.element(f"IfcLightFixture_{name}")
        cuboid_solid(obj, (cx - 0.3, cy - 0.3, HEIGHT - 0.06), (cx + 0.3, cy + 0.3, HEIGHT), "housing", bottom="lamp")
        lamps.append([cx, cy, HEIGHT - 0.06])

    base = os.path.splitext(out)[0]
    with open(base + ".mtl", "w") as f:
        f.write("# dynrad storey sample materials (make_storey.py)\n")
        for name, kd, ke in MATERIALS:
            f.write(f"newmtl {name}\nKd {kd} {kd} {kd}\n")
            if ke:
                f.write(f"Ke {ke} {ke} {ke}\n")
            f.write("\n")
    triangles = 0
    with open(out, "w") as f:
        f.write("# dynrad storey sample: one storey as an IFC export gives it (make_storey.py); metres, z up\n")
        f.write(f"mtllib {os.path.basename(base)}.mtl\n")
        for p in obj.v:
            f.write("v %.6f %.6f %.6f\n" % p)
        for name, faces in obj.groups:
            f.write(f"g {name}\n")
            current = None
            for material, tri in faces:
                if material != current:
                    f.write(f"usemtl {material}\n")
                    current = material
                f.write("f %d %d %d\n" % tri)
                triangles += 1
    layout = {
        "floor_height": 0.0,
        "ceiling_height": HEIGHT,
        "rooms": [{"name": n, "rectangle": list(r)} for n, r in rooms.items()],
        "furniture": furniture,
        "doors": doors,
        "windows": windows,
        "lamps": lamps,
    }
    with open(base + "_layout.json", "w") as f:
        json.dump(layout, f, indent=1)
        f.write("\n")
    print(f"{out}: {len(obj.v)} vertices, {triangles} triangles, {len(obj.groups)} elements")


if __name__ == "__main__":
    main()
