#!/usr/bin/env python3
"""Generates a building floor for scale tests: a grid of rooms with door openings,
windows in the outer walls, furniture blocks and a ceiling light per room.

    samples/make_building.py OUT.obj [--rooms NX NY] [--cell SIZE]

Every rectangle is tessellated into cells of at most --cell metres, which sets the
triangle count (two per cell): with the default 6 x 5 rooms, --cell 0.25 gives about
100k triangles and --cell 0.08 about 1M. Writes OUT.obj and OUT.mtl beside it. The big
files are not in the repository: generate them.

Geometry: rooms 5 m x 4 m x 3 m; interior walls 0.1 m thick (two faces), doors 1 m x
2.1 m in every interior wall; windows 1.5 m x 1.2 m in the outer walls (openings: light
leaves through them, the report counts it as escaped); one table (a box) per room and
a 1 m x 0.5 m ceiling light.
"""
import argparse
import math
import os

ROOM_X, ROOM_Y, HEIGHT, WALL = 5.0, 4.0, 3.0, 0.1
DOOR_W, DOOR_H = 1.0, 2.1
WIN_W, WIN_H, SILL = 1.5, 1.2, 0.9


class Obj:
    def __init__(self, cell):
        self.cell = cell
        self.v = []
        self.f = []  # (material, [indices])
        self.index = {}

    def vertex(self, p):
        key = tuple(round(c, 6) for c in p)
        if key not in self.index:
            self.index[key] = len(self.v) + 1
            self.v.append(key)
        return self.index[key]

    def rect(self, material, origin, u, v):
        """Rectangle origin + s*u + t*v, s, t in [0, 1], facing u x v, tessellated."""
        lu = math.sqrt(sum(c * c for c in u))
        lv = math.sqrt(sum(c * c for c in v))
        if lu < 1e-9 or lv < 1e-9:
            return
        nu = max(1, math.ceil(lu / self.cell - 1e-9))
        nv = max(1, math.ceil(lv / self.cell - 1e-9))
        def at(i, j):
            s, t = i / nu, j / nv
            return self.vertex([origin[k] + s * u[k] + t * v[k] for k in range(3)])
        for i in range(nu):
            for j in range(nv):
                self.f.append((material, [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]))

    def box(self, material, lo, hi):
        (x0, y0, z0), (x1, y1, z1) = lo, hi
        dx, dy, dz = x1 - x0, y1 - y0, z1 - z0
        self.rect(material, (x0, y0, z1), (dx, 0, 0), (0, dy, 0))        # top, facing +z
        self.rect(material, (x0, y0, z0), (dx, 0, 0), (0, 0, dz))        # -y
        self.rect(material, (x1, y1, z0), (-dx, 0, 0), (0, 0, dz))       # +y
        self.rect(material, (x0, y1, z0), (0, -dy, 0), (0, 0, dz))       # -x
        self.rect(material, (x1, y0, z0), (0, dy, 0), (0, 0, dz))        # +x


def wall_with_opening(obj, material, origin, along, length, normal_sign, opening):
    """A vertical wall face from origin, `along` a unit axis ('x' or 'y'), facing
    normal_sign along the other horizontal axis, with an optional opening
    (start, width, bottom, top) measured along the wall."""
    ax = {'x': (1, 0, 0), 'y': (0, 1, 0)}[along]
    up = (0, 0, 1)
    def piece(s0, s1, z0, z1):
        if s1 - s0 < 1e-9 or z1 - z0 < 1e-9:
            return
        o = [origin[k] + s0 * ax[k] for k in range(3)]
        o[2] += z0
        u = [(s1 - s0) * c for c in ax]
        v = [0, 0, z1 - z0]
        # Facing: u x v must point along normal_sign times the wall normal.
        cross = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
        axis = 1 if along == 'x' else 0
        if cross[axis] * normal_sign < 0:
            o = [o[k] + u[k] for k in range(3)]
            u = [-c for c in u]
        obj.rect(material, o, u, v)
    if opening is None:
        piece(0, length, 0, HEIGHT)
        return
    s, w, bottom, top = opening
    piece(0, s, 0, HEIGHT)
    piece(s + w, length, 0, HEIGHT)
    piece(s, s + w, 0, bottom)
    piece(s, s + w, top, HEIGHT)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out")
    parser.add_argument("--rooms", nargs=2, type=int, default=[6, 5])
    parser.add_argument("--cell", type=float, default=0.25)
    args = parser.parse_args()
    nx, ny = args.rooms
    obj = Obj(args.cell)
    for i in range(nx):
        for j in range(ny):
            x0, y0 = i * ROOM_X, j * ROOM_Y
            # Inner extent of the room: half a wall in from shared walls.
            ix0 = x0 + (WALL / 2 if i > 0 else 0)
            ix1 = x0 + ROOM_X - (WALL / 2 if i < nx - 1 else 0)
            iy0 = y0 + (WALL / 2 if j > 0 else 0)
            iy1 = y0 + ROOM_Y - (WALL / 2 if j < ny - 1 else 0)
            lx, ly = ix1 - ix0, iy1 - iy0
            obj.rect("floor", (ix0, iy0, 0), (lx, 0, 0), (0, ly, 0))
            obj.rect("ceiling", (ix0, iy0, HEIGHT), (0, ly, 0), (lx, 0, 0))
            door = lambda length: (length / 2 - DOOR_W / 2, DOOR_W, 0, DOOR_H)
            window = lambda length: (length / 2 - WIN_W / 2, WIN_W, SILL, SILL + WIN_H)
            # Walls facing into the room; shared walls get a door, outer walls a window.
            wall_with_opening(obj, "wall", (ix0, iy0, 0), 'x', lx, +1, door(lx) if j > 0 else window(lx))
            wall_with_opening(obj, "wall", (ix0, iy1, 0), 'x', lx, -1, door(lx) if j < ny - 1 else window(lx))
            wall_with_opening(obj, "wall", (ix0, iy0, 0), 'y', ly, +1, door(ly) if i > 0 else window(ly))
            wall_with_opening(obj, "wall", (ix1, iy0, 0), 'y', ly, -1, door(ly) if i < nx - 1 else window(ly))
            # Door reveals (the wall's thickness inside the opening) are left open.
            cx, cy = (ix0 + ix1) / 2, (iy0 + iy1) / 2
            obj.box("furniture", (cx - 0.8, cy - 0.45, 0), (cx + 0.8, cy + 0.45, 0.75))
            obj.rect("light", (cx - 0.5, cy - 0.25, HEIGHT - 0.01), (0, 0.5, 0), (1.0, 0, 0))
    base = os.path.splitext(args.out)[0]
    mtl = base + ".mtl"
    with open(mtl, "w") as f:
        f.write("# dynrad building floor materials\n")
        for name, kd, ke in [("floor", 0.3, 0), ("ceiling", 0.8, 0), ("wall", 0.6, 0), ("furniture", 0.4, 0),
                             ("light", 0.8, 30)]:
            f.write(f"newmtl {name}\nKd {kd} {kd} {kd}\nKe {ke} {ke} {ke}\n\n")
    with open(args.out, "w") as f:
        f.write(f"# dynrad building floor: {nx} x {ny} rooms, cells of {args.cell} m\n")
        f.write(f"mtllib {os.path.basename(mtl)}\n")
        for p in obj.v:
            f.write("v %.6g %.6g %.6g\n" % p)
        current = None
        triangles = 0
        for material, idx in obj.f:
            if material != current:
                f.write(f"usemtl {material}\n")
                current = material
            f.write("f " + " ".join(str(k) for k in idx) + "\n")
            triangles += len(idx) - 2
    print(f"{args.out}: {len(obj.v)} vertices, {len(obj.f)} polygons, {triangles} triangles")


if __name__ == "__main__":
    main()
