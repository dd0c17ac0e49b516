#!/usr/bin/env python3
"""Generates rooms for daylight: a 6 x 4 x 2.8 m room (z up, north +y) with a window in
its south wall (y = 0, 2.4 x 1.4 m, sill 0.9 m) and one in its east wall (x = 6, 1.6 x
1.4 m), glazed (transmittance 0.7: MTL d 0.3); and the same room closed on its sides
with a 1.2 x 1.2 m glazed skylight in the middle of its ceiling.

    samples/make_daylight_room.py [DIR]     (default: beside this script)

Writes daylight_room.obj and daylight_skylight.obj with daylight_room.mtl. Walls, floor
and ceiling are single faces facing into the room (the light from outside reaches them
only through the windows). The scene files daylight_overcast.json, daylight_clear.json
and daylight_skylight.json light them.
"""
import os
import sys

W, D, H = 6.0, 4.0, 2.8


class Obj:
    def __init__(self):
        self.v, self.f = [], []

    def quad(self, a, b, c, d, material):
        """Counter-clockwise seen from the front."""
        base = len(self.v) + 1
        self.v += [a, b, c, d]
        self.f.append((material, [base, base + 1, base + 2, base + 3]))

    def write(self, path):
        with open(path, "w") as out:
            out.write("# written by samples/make_daylight_room.py\nmtllib daylight_room.mtl\n")
            for p in self.v:
                out.write("v %.4f %.4f %.4f\n" % p)
            current = None
            for material, face in self.f:
                if material != current:
                    out.write("usemtl %s\n" % material)
                    current = material
                out.write("f " + " ".join(str(i) for i in face) + "\n")


def wall_with_hole(obj, origin, along, up, length, height, hole, material):
    """A wall rectangle from `origin` spanning `along` and `up` (unit vectors, ordered so
    that along x up points into the room), with the rectangle hole = (u0, v0, u1, v1)
    cut out; the hole gets a glass quad."""
    def at(u, v):
        return tuple(origin[i] + along[i] * u + up[i] * v for i in range(3))
    u0, v0, u1, v1 = hole
    for a, b, c, d in (((0, 0), (length, 0), (length, v0), (0, v0)),          # below
                       ((0, v1), (length, v1), (length, height), (0, height)),  # above
                       ((0, v0), (u0, v0), (u0, v1), (0, v1)),                  # left
                       ((u1, v0), (length, v0), (length, v1), (u1, v1))):      # right
        obj.quad(at(*a), at(*b), at(*c), at(*d), material)
    obj.quad(at(u0, v0), at(u1, v0), at(u1, v1), at(u0, v1), "glass")


def room(skylight):
    o = Obj()
    o.quad((0, 0, 0), (W, 0, 0), (W, D, 0), (0, D, 0), "floor")  # facing up
    if skylight:
        s0, s1 = (W - 1.2) / 2, (D - 1.2) / 2
        x0, x1, y0, y1 = s0, s0 + 1.2, s1, s1 + 1.2
        for a, b, c, d in (((0, 0), (0, D), (x0, D), (x0, 0)), ((x1, 0), (x1, D), (W, D), (W, 0)),
                           ((x0, 0), (x0, y0), (x1, y0), (x1, 0)), ((x0, y1), (x0, D), (x1, D), (x1, y1))):
            o.quad((a[0], a[1], H), (b[0], b[1], H), (c[0], c[1], H), (d[0], d[1], H), "ceiling")  # facing down
        o.quad((x0, y0, H), (x0, y1, H), (x1, y1, H), (x1, y0, H), "glass")
        o.quad((W, 0, 0), (0, 0, 0), (0, 0, H), (W, 0, H), "wall")  # south, facing +y
        o.quad((W, D, 0), (W, 0, 0), (W, 0, H), (W, D, H), "wall")  # east, facing -x
    else:
        o.quad((0, 0, H), (0, D, H), (W, D, H), (W, 0, H), "ceiling")  # facing down
        # South wall (y = 0) faces +y: along +x, up +z gives x cross z = -y, so go along -x from x = W.
        wall_with_hole(o, (W, 0, 0), (-1, 0, 0), (0, 0, 1), W, H, (W / 2 - 1.2, 0.9, W / 2 + 1.2, 2.3), "wall")
        # East wall (x = W) faces -x: along -y from y = D, up +z: (-y) x z = -x.
        wall_with_hole(o, (W, D, 0), (0, -1, 0), (0, 0, 1), D, H, (D / 2 - 0.8, 0.9, D / 2 + 0.8, 2.3), "wall")
    o.quad((0, D, 0), (W, D, 0), (W, D, H), (0, D, H), "wall")  # north, facing -y (x cross z)
    o.quad((0, 0, 0), (0, D, 0), (0, D, H), (0, 0, H), "wall")  # west, facing +x (y cross z)
    return o


def main():
    out_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    room(False).write(os.path.join(out_dir, "daylight_room.obj"))
    room(True).write(os.path.join(out_dir, "daylight_skylight.obj"))
    with open(os.path.join(out_dir, "daylight_room.mtl"), "w") as out:
        out.write("# written by samples/make_daylight_room.py\n")
        for name, rho in (("floor", 0.3), ("wall", 0.6), ("ceiling", 0.8)):
            out.write("newmtl %s\nKd %.2f %.2f %.2f\n\n" % (name, rho, rho, rho))
        out.write("newmtl glass\nKd 0 0 0\nd 0.3\n")


if __name__ == "__main__":
    main()
