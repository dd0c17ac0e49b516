#!/usr/bin/env python3
"""Generates a furnished multi-storey office building the way architects' models are
exported (IFC and the like): every element one or more closed, triangulated solids, the
solids overlapping where elements meet, nothing imprinted on anything else.

    samples/make_office.py OUT_PREFIX --storeys N [--rooms NX NY] [--seed S] [--lamps L]

Writes OUT_PREFIX.obj, OUT_PREFIX.mtl and OUT_PREFIX.json (a dynrad scene: the mesh,
point luminaires and one work-plane grid per office). Standard library only.

Building (metres, z up, origin at the south-west corner of the outer wall axes):
- a grid of NX x NY offices (default 6 x 3) on 5 m x 4 m wall axes, no corridor: every
  inner wall has a door (0.9 x 2.1 m) into each neighbouring office, so the rooms of the
  middle row have no window;
- storeys 3 m floor to floor: slabs 0.25 m thick (clear height 2.75 m), the floor slab
  of storey k at z = 3k - 0.25 .. 3k, a roof slab over the top storey; the slabs run
  three quarters of the way into the outer walls;
- outer walls 0.3 m thick, one solid per wall and storey, from the bottom of the floor
  slab to the top of the ceiling slab, so they run through both slabs and overlap the
  walls of the storeys above and below; the south and north walls run over the corners,
  the west and east walls end at the south and north walls' axes;
- inner walls 0.12 m thick standing on the floor slab and touching the ceiling slab,
  each running the full length of the building (the walls along x and along y cross
  each other) and into the outer walls up to their axes;
- window openings (no glass) 1.5 x 1.5 m, sill at 0.9 m: two per office on the south and
  north facades, one per end office on the west and east facades; each with a frame of
  profile boxes (frame, mullion, two casements with handles), an inner window board and
  an outer metal sill, and a radiator under it (30 thin fins on two header pipes,
  brackets, valve, riser into the slab);
- per office: two desks back to back (top, four cylindrical legs, side rails, modesty
  panel), a drawer pedestal with handles under each, a monitor and keyboard on each,
  two office chairs (five-star base with casters, gas column, seat, back, armrests), a
  shelf with boards and books, a cupboard with doors and handles, a waste bin, perhaps a
  plant; skirting boards along the walls; a block frame in every door opening.
Big faces (walls, slabs) stay a few triangles each; the triangle count comes from the
furniture, frames and radiators, as in a real model. Nothing touches along an edge of
another solid where it can be avoided: parts that meet overlap a little (a leg runs
5 mm into the desk top, a skirting 5 mm into the wall), so the overlaps are for
imprinting to find. The exceptions are the building's outer corners, where the walls of
two storeys share a corner line through the slab between them.

Furniture placement (desk offsets, chair turns, books, plants) varies a little with
--seed; a given seed always gives the same building (default seed 1).

Sizes with the default 6 x 3 offices (30.3 x 12.3 m outside), seed 1:
    storeys   triangles   vertices
       1         87,516     55,760
       2        174,600    111,248
       4        348,408    222,024
       8        696,432    443,816
(every face is written as a triangle; measured with this script.)

The scene JSON has two point luminaires of 3000 lm per office, 0.2 m under the ceiling
("s1_r3_a" is storey 1, office 3, the western one; --lamps L hangs L of 6000/L lm
instead, for how a solve grows with the luminaires at the same light), and a grid per office at 0.8 m above
its floor with a 0.5 m border ("s1_r3").
"""
import argparse
import json
import math
import os
import random

STOREY = 3.0               # floor to floor
SLAB = 0.25
CLEAR = STOREY - SLAB      # floor slab top to ceiling slab bottom
ROOM_X, ROOM_Y = 5.0, 4.0  # wall axes
OUTER, INNER = 0.3, 0.12
SLAB_IN = 0.225            # how far the slabs run into the outer walls (from their outer face)
DOOR_W, DOOR_H = 0.9, 2.1
WIN_W, WIN_H, SILL = 1.5, 1.5, 0.9
DOOR_X = 0.96              # door in a wall along x: from x_i + DOOR_X (x_i the office's west axis)
DOOR_Y = 2.59              # door in a wall along y: from y_j + DOOR_Y

# name, Kd (linear reflectance, sRGB-ish numbers)
MATERIALS = [
    ("plaster", (0.78, 0.76, 0.72)), ("floor", (0.38, 0.34, 0.30)), ("ceiling", (0.80, 0.80, 0.80)),
    ("concrete", (0.45, 0.45, 0.43)), ("roof", (0.30, 0.30, 0.30)),
    ("wood", (0.55, 0.42, 0.30)), ("laminate", (0.62, 0.58, 0.52)), ("metal", (0.50, 0.50, 0.52)),
    ("fabric", (0.22, 0.25, 0.32)), ("plastic", (0.08, 0.08, 0.08)), ("screen", (0.04, 0.04, 0.05)),
    ("frame", (0.75, 0.75, 0.74)), ("radiator", (0.78, 0.78, 0.76)), ("skirting", (0.60, 0.58, 0.55)),
    ("book_red", (0.50, 0.12, 0.10)), ("book_blue", (0.10, 0.18, 0.42)), ("book_cream", (0.68, 0.62, 0.48)),
    ("book_green", (0.14, 0.32, 0.18)), ("pot", (0.50, 0.30, 0.20)), ("leaf", (0.10, 0.28, 0.08)),
]
BOOKS = ["book_red", "book_blue", "book_cream", "book_green"]


# --- geometry -------------------------------------------------------------------------

def add(p, q):
    return (p[0] + q[0], p[1] + q[1], p[2] + q[2])


def scale(p, s):
    return (p[0] * s, p[1] * s, p[2] * s)


def sub(p, q):
    return (p[0] - q[0], p[1] - q[1], p[2] - q[2])


def cross(p, q):
    return (p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0])


def dot(p, q):
    return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]


class Frame:
    """A local coordinate frame: point (x, y, z) -> origin + x ex + y ey + z ez. The axes
    need not be right-handed: solids are turned outward after they are built."""

    def __init__(self, origin, ex=(1, 0, 0), ey=(0, 1, 0), ez=(0, 0, 1)):
        self.o, self.ex, self.ey, self.ez = tuple(origin), ex, ey, ez

    def __call__(self, x, y, z):
        o, a, b, c = self.o, self.ex, self.ey, self.ez
        return (o[0] + x * a[0] + y * b[0] + z * c[0], o[1] + x * a[1] + y * b[1] + z * c[1],
                o[2] + x * a[2] + y * b[2] + z * c[2])

    def turned(self, degrees, at=(0, 0, 0)):
        """The frame turned about its z axis through local point `at`."""
        c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
        ex = add(scale(self.ex, c), scale(self.ey, s))
        ey = add(scale(self.ex, -s), scale(self.ey, c))
        return Frame(self(*at), ex, ey, self.ez)

    def moved(self, x, y, z):
        return Frame(self(x, y, z), self.ex, self.ey, self.ez)


WORLD = Frame((0, 0, 0))


class Obj:
    """Triangles grouped by element; each element is one or more closed solids."""

    def __init__(self):
        self.v, self.index = [], {}
        self.groups = []  # (name, [(material, (i, j, k))])
        self.solid = None
        self.solids = 0

    def vertex(self, p):
        key = tuple(round(c, 6) + 0.0 for c in p)
        if key not in self.index:
            self.index[key] = len(self.v) + 1
            self.v.append(key)
        return self.index[key]

    def element(self, name):
        self.groups.append((name, []))

    def begin(self):
        self.solid = []

    def tri(self, material, a, b, c):
        self.solid.append((material, (self.vertex(a), self.vertex(b), self.vertex(c))))

    def poly(self, material, pts):
        """A convex polygon, counter-clockwise seen from the side it faces, as a fan."""
        for k in range(1, len(pts) - 1):
            self.tri(material, pts[0], pts[k], pts[k + 1])

    def end(self):
        """Checks the solid is closed and manifold (every edge used once each way),
        turns it outward and adds it to the current element."""
        tris, self.solid = self.solid, None
        edges = {}
        for _, t in tris:
            for k in range(3):
                e = (t[k], t[(k + 1) % 3])
                edges[e] = edges.get(e, 0) + 1
        for (a, b), n in edges.items():
            if n != 1 or edges.get((b, a)) != 1:
                raise AssertionError(f"solid {self.solids} in {self.groups[-1][0]} is not closed at "
                                     f"{self.v[a - 1]} - {self.v[b - 1]}")
        o = self.v[tris[0][1][0] - 1]
        volume = 0.0
        for _, (i, j, k) in tris:
            volume += dot(sub(self.v[i - 1], o), cross(sub(self.v[j - 1], o), sub(self.v[k - 1], o)))
        if abs(volume) < 1e-12:
            raise AssertionError(f"solid {self.solids} in {self.groups[-1][0]} has no volume")
        if volume < 0:
            tris = [(m, (i, k, j)) for m, (i, j, k) in tris]
        self.groups[-1][1].extend(tris)
        self.solids += 1

    def triangles(self):
        return sum(len(faces) for _, faces in self.groups)


def box(obj, frame, lo, hi, material, faces=None):
    """A closed box lo..hi in `frame`; `faces` maps '+z', '-z', '+x', ... to other materials."""
    faces = faces or {}
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    assert x1 > x0 and y1 > y0 and z1 > z0, (lo, hi)
    p = lambda i, j, k: frame((x0, x1)[i], (y0, y1)[j], (z0, z1)[k])
    m = lambda key: faces.get(key, material)
    obj.begin()
    obj.poly(m("+z"), [p(0, 0, 1), p(1, 0, 1), p(1, 1, 1), p(0, 1, 1)])
    obj.poly(m("-z"), [p(0, 0, 0), p(0, 1, 0), p(1, 1, 0), p(1, 0, 0)])
    obj.poly(m("-y"), [p(0, 0, 0), p(1, 0, 0), p(1, 0, 1), p(0, 0, 1)])
    obj.poly(m("+y"), [p(1, 1, 0), p(0, 1, 0), p(0, 1, 1), p(1, 1, 1)])
    obj.poly(m("-x"), [p(0, 1, 0), p(0, 0, 0), p(0, 0, 1), p(0, 1, 1)])
    obj.poly(m("+x"), [p(1, 0, 0), p(1, 1, 0), p(1, 1, 1), p(1, 0, 1)])
    obj.end()


def prism(obj, frame, outline, z0, z1, material, cap=None):
    """A vertical prism in `frame`: the convex counter-clockwise polygon `outline`
    ([(x, y), ...]) from z0 to z1."""
    cap = cap or material
    bottom = [frame(x, y, z0) for x, y in outline]
    top = [frame(x, y, z1) for x, y in outline]
    n = len(outline)
    obj.begin()
    obj.poly(cap, top)
    obj.poly(cap, bottom[::-1])
    for k in range(n):
        obj.poly(material, [bottom[k], bottom[(k + 1) % n], top[(k + 1) % n], top[k]])
    obj.end()


def circle(cx, cy, r, sides, phase=0.0):
    return [(cx + r * math.cos(phase + 2 * math.pi * k / sides), cy + r * math.sin(phase + 2 * math.pi * k / sides))
            for k in range(sides)]


def cylinder(obj, frame, c, r, z0, z1, sides, material, axis="z", phase=0.0, cap=None):
    """A cylinder of `sides` sides about a line through local point c along `axis`,
    from z0 to z1 along that axis (c's own coordinate on it is ignored)."""
    if axis == "z":
        f = frame.moved(c[0], c[1], 0)
    elif axis == "x":  # local (u, v, w) -> (w, u, v): the axis along x
        f = Frame(frame(0, c[1], c[2]), frame.ey, frame.ez, frame.ex)
    else:  # along y: (u, v, w) -> (u, w, v) about (c[0], ., c[2])
        f = Frame(frame(c[0], 0, c[2]), frame.ex, frame.ez, frame.ey)
    prism(obj, f, circle(0, 0, r, sides, phase), z0, z1, material, cap)


def wall(obj, frame, length, t0, t1, z0, z1, openings, material="plaster"):
    """A wall from s = 0 to `length` along frame x, across frame y from t0 to t1, from z0
    to z1, with rectangular openings (s0, s1, zb, zt) through it: the box minus the
    openings, as one closed solid. It is cut into cells on a grid through the openings'
    edges (so the solid is conforming); faces are the cells' sides between solid and
    empty, so a big face stays a few triangles."""
    ss = sorted({0.0, length} | {o[0] for o in openings} | {o[1] for o in openings})
    zs = sorted({z0, z1} | {o[2] for o in openings} | {o[3] for o in openings})
    ns, nz = len(ss) - 1, len(zs) - 1
    for o in openings:
        assert 0 < o[0] < o[1] < length and z0 <= o[2] < o[3] < z1, o

    def solid(i, j):
        if i < 0 or j < 0 or i >= ns or j >= nz:
            return False
        sm, zm = (ss[i] + ss[i + 1]) / 2, (zs[j] + zs[j + 1]) / 2
        return not any(o[0] < sm < o[1] and o[2] < zm < o[3] for o in openings)

    w = frame
    obj.begin()
    for i in range(ns):
        for j in range(nz):
            if not solid(i, j):
                continue
            sa, sb, za, zb = ss[i], ss[i + 1], zs[j], zs[j + 1]
            obj.poly(material, [w(sa, t0, za), w(sb, t0, za), w(sb, t0, zb), w(sa, t0, zb)])  # -t side
            obj.poly(material, [w(sb, t1, za), w(sa, t1, za), w(sa, t1, zb), w(sb, t1, zb)])  # +t side
            if not solid(i - 1, j):
                obj.poly(material, [w(sa, t1, za), w(sa, t0, za), w(sa, t0, zb), w(sa, t1, zb)])
            if not solid(i + 1, j):
                obj.poly(material, [w(sb, t0, za), w(sb, t1, za), w(sb, t1, zb), w(sb, t0, zb)])
            if not solid(i, j - 1):
                obj.poly(material, [w(sa, t0, za), w(sa, t1, za), w(sb, t1, za), w(sb, t0, za)])
            if not solid(i, j + 1):
                obj.poly(material, [w(sa, t1, zb), w(sa, t0, zb), w(sb, t0, zb), w(sb, t1, zb)])
    obj.end()


# --- building elements -------------------------------------------------------------------
# Furniture is built in its own frame: x to the right, y forward (away from the wall it
# stands against, or towards the desk for a chair), z up from the floor.

def door_frame(obj, f, a, b):
    """A block frame in a door opening a..b of an inner wall (wall frame f: s along it,
    t across from its axis, z from the floor): two jambs and a head, proud of both
    faces by 2 cm and running 3 cm into the wall."""
    h = INNER / 2
    box(obj, f, (a - 0.06, -h - 0.02, 0), (a + 0.03, h + 0.02, DOOR_H + 0.03), "wood")
    box(obj, f, (b - 0.03, -h - 0.02, 0), (b + 0.06, h + 0.02, DOOR_H + 0.03), "wood")
    box(obj, f, (a - 0.03, -h - 0.015, DOOR_H - 0.025), (b + 0.03, h + 0.015, DOOR_H + 0.05), "wood")


def window_frame(obj, f, a, b, zs, zh):
    """Frame, mullion, two casements, window board and outer sill in a window opening
    a..b, zs..zh of an outer wall (wall frame f: t across from the axis, inside at +t)."""
    m = (a + b) / 2
    fr = "frame"
    # Outer frame: jambs 2 cm into the wall, head and sill profile between them.
    box(obj, f, (a - 0.02, -0.03, zs - 0.02), (a + 0.07, 0.04, zh + 0.02), fr)
    box(obj, f, (b - 0.07, -0.03, zs - 0.02), (b + 0.02, 0.04, zh + 0.02), fr)
    box(obj, f, (a + 0.04, -0.028, zs - 0.015), (b - 0.04, 0.038, zs + 0.07), fr)
    box(obj, f, (a + 0.04, -0.028, zh - 0.07), (b - 0.04, 0.038, zh + 0.015), fr)
    box(obj, f, (m - 0.035, -0.026, zs + 0.05), (m + 0.035, 0.036, zh - 0.05), fr)  # mullion
    # Casements: a sash of four profiles in each light, overlapping the frame by 1 cm.
    for s0, s1, hinge_left in ((a + 0.06, m - 0.025, True), (m + 0.025, b - 0.06, False)):
        z0, z1 = zs + 0.06, zh - 0.06
        box(obj, f, (s0, 0.0, z0), (s0 + 0.065, 0.05, z1), fr)
        box(obj, f, (s1 - 0.065, 0.0, z0), (s1, 0.05, z1), fr)
        box(obj, f, (s0 + 0.04, 0.003, z0), (s1 - 0.04, 0.047, z0 + 0.075), fr)
        box(obj, f, (s0 + 0.04, 0.003, z1 - 0.075), (s1 - 0.04, 0.047, z1), fr)
        hs = s1 - 0.035 if hinge_left else s0 + 0.035  # handle on the side away from the hinge
        zc = (z0 + z1) / 2
        box(obj, f, (hs - 0.015, 0.045, zc - 0.03), (hs + 0.015, 0.065, zc + 0.03), "metal")
        box(obj, f, (hs - 0.009, 0.06, zc - 0.12), (hs + 0.009, 0.078, zc + 0.008), "metal")
    box(obj, f, (a - 0.04, 0.035, zs - 0.01), (b + 0.04, OUTER / 2 + 0.04, zs + 0.02), "wood")  # window board
    box(obj, f, (a - 0.03, -OUTER / 2 - 0.05, zs - 0.035), (b + 0.03, -0.02, zs - 0.005), "metal")  # outer sill


def radiator(obj, f, s0, s1):
    """A radiator from s0 to s1 under a window (wall frame f, t from the axis): thin
    fins on two header pipes, two brackets into the wall, a valve and a riser."""
    face = OUTER / 2
    pitch = 0.04
    n = int(round((s1 - s0) / pitch))
    centres = [s0 + pitch * (k + 0.5) for k in range(n)]
    for c in centres:
        box(obj, f, (c - 0.006, face + 0.06, 0.12), (c + 0.006, face + 0.14, 0.68), "radiator")
    for z in (0.16, 0.64):
        cylinder(obj, f, (0, face + 0.10, z), 0.016, s0 - 0.02, s1 + 0.02, 8, "radiator", axis="x")
    for c in (centres[2], centres[-3]):
        box(obj, f, (c - 0.015, face - 0.01, 0.55), (c + 0.015, face + 0.065, 0.58), "metal")
    cylinder(obj, f, (s1 + 0.005, face + 0.10, 0), 0.012, 0.62, 0.75, 8, "metal")  # valve
    cylinder(obj, f, (s0 - 0.005, face + 0.10, 0), 0.01, -0.05, 0.17, 8, "metal")  # riser into the slab


def desk(obj, f):
    """1.6 x 0.8 m desk, 0.74 m high, the user at -y: top, four round legs, side rails,
    modesty panel at +y."""
    w, d, top = 1.6, 0.8, 0.715
    box(obj, f, (0, 0, top), (w, d, top + 0.025), "laminate")
    legs = [(0.06, 0.06), (w - 0.06, 0.06), (0.06, d - 0.06), (w - 0.06, d - 0.06)]
    for x, y in legs:
        cylinder(obj, f, (x, y, 0), 0.025, 0.0, top + 0.005, 12, "metal")
    for x in (0.06, w - 0.06):
        box(obj, f, (x - 0.012, 0.06, top - 0.07), (x + 0.012, d - 0.06, top + 0.003), "metal")
    box(obj, f, (0.06, d - 0.072, 0.3), (w - 0.06, d - 0.052, top + 0.002), "metal")


def pedestal(obj, f):
    """Drawer pedestal 0.42 x 0.58 x 0.6 m, drawers at -y: body, three fronts, handles."""
    w, d, h = 0.42, 0.58, 0.6
    box(obj, f, (0, 0.02, 0.0), (w, d, h), "laminate")
    for k, (z0, z1) in enumerate(((0.02, 0.2), (0.21, 0.39), (0.4, 0.58))):
        box(obj, f, (0.006, 0.0, z0), (w - 0.006, 0.022, z1), "laminate")
        zc = z1 - 0.04
        box(obj, f, (0.12, -0.026, zc - 0.006), (w - 0.12, -0.014, zc + 0.006), "metal")
        for x in (0.135, w - 0.135):
            box(obj, f, (x - 0.005, -0.016, zc - 0.005), (x + 0.005, 0.002, zc + 0.005), "metal")


def monitor(obj, f):
    """Monitor seen from -y, standing on the desk top (frame z at the top)."""
    box(obj, f, (-0.11, -0.08, 0.0), (0.11, 0.08, 0.012), "plastic")  # foot
    box(obj, f, (-0.025, 0.02, 0.008), (0.025, 0.04, 0.32), "plastic")  # neck
    box(obj, f, (-0.09, 0.03, 0.15), (0.09, 0.07, 0.33), "plastic")  # back housing
    box(obj, f, (-0.28, -0.005, 0.1), (0.28, 0.032, 0.44), "plastic", {"-y": "screen"})


def keyboard(obj, f):
    box(obj, f, (-0.22, -0.07, 0.0), (0.22, 0.07, 0.022), "plastic")
    box(obj, f, (0.29, -0.03, 0.0), (0.35, 0.03, 0.03), "plastic")  # mouse


def chair(obj, f, rng):
    """Office chair, facing +y, seat centre at the origin."""
    spin = rng.uniform(0, 72)
    cylinder(obj, f, (0, 0, 0), 0.045, 0.05, 0.11, 10, "plastic")  # hub
    for k in range(5):
        a = f.turned(spin + 72 * k)
        box(obj, a, (0.03, -0.018, 0.065), (0.31, 0.018, 0.095), "plastic")  # arm of the star
        box(obj, a, (0.28, -0.012, 0.04), (0.32, 0.012, 0.07), "plastic")  # caster fork
        r = 0.026
        cylinder(obj, a, (0.3, 0, r * math.cos(math.pi / 8)), r, -0.011, 0.011, 8, "plastic", axis="y",
                 phase=math.pi / 8)  # wheel, a flat side on the floor
    cylinder(obj, f, (0, 0, 0), 0.025, 0.09, 0.45, 12, "metal")  # gas column
    box(obj, f, (-0.2, -0.19, 0.43), (0.2, 0.19, 0.452), "metal")  # seat plate
    box(obj, f, (-0.24, -0.22, 0.45), (0.24, 0.24, 0.51), "fabric")  # seat cushion
    box(obj, f, (-0.03, -0.26, 0.425), (0.03, -0.1, 0.445), "metal")  # back support, under the seat
    box(obj, f, (-0.03, -0.265, 0.43), (0.03, -0.24, 0.75), "metal")  # and up
    box(obj, f, (-0.22, -0.31, 0.6), (0.22, -0.255, 1.05), "fabric")  # backrest
    for sx in (-1, 1):
        x0, x1 = sorted((sx * 0.22, sx * 0.25))
        box(obj, f, (x0, -0.05, 0.46), (x1, 0.0, 0.70), "plastic")  # armrest post
        x0, x1 = sorted((sx * 0.205, sx * 0.275))
        box(obj, f, (x0, -0.16, 0.69), (x1, 0.12, 0.715), "plastic")  # armrest pad


def shelf(obj, f, rng):
    """Open shelf 1.0 x 0.35 x 2.0 m, its back at y = 0.35 (against a wall): sides,
    plinth, six boards, back panel and books on five boards."""
    w, d, h, t = 1.0, 0.35, 2.0, 0.02
    box(obj, f, (0, 0, 0), (t, d, h), "wood")
    box(obj, f, (w - t, 0, 0), (w, d, h), "wood")
    box(obj, f, (t - 0.005, 0.03, 0), (w - t + 0.005, 0.32, 0.07), "wood")  # plinth
    levels = [0.07, 0.45, 0.83, 1.21, 1.59, h - 0.02]
    for z in levels:
        box(obj, f, (t - 0.01, 0.01, z), (w - t + 0.01, d - 0.012, z + 0.02), "wood")
    box(obj, f, (t - 0.005, d - 0.015, 0.05), (w - t + 0.005, d - 0.002, h - 0.01), "wood")  # back panel
    for z in levels[:-1]:
        x = t + rng.uniform(0.004, 0.03)
        while True:
            bw = rng.uniform(0.018, 0.05)
            if x + bw > w - t - 0.004:
                break
            if rng.random() < 0.12:  # a gap in the row
                x += rng.uniform(0.04, 0.12)
                continue
            bh = rng.uniform(0.17, 0.3)
            bd = rng.uniform(0.15, 0.24)
            y0 = rng.uniform(0.015, 0.05)
            box(obj, f, (x, y0, z + 0.02), (x + bw, y0 + bd, z + 0.02 + bh), rng.choice(BOOKS))
            x += bw + rng.uniform(0.002, 0.006)


def cupboard(obj, f):
    """Cupboard 1.2 x 0.45 x 2.0 m, its back at y = 0.45: body on a recessed plinth,
    two doors, two bar handles, a cornice."""
    w, d, h = 1.2, 0.45, 2.0
    box(obj, f, (0.02, 0.05, 0), (w - 0.02, d - 0.02, 0.08), "wood")  # plinth
    box(obj, f, (0, 0.02, 0.08), (w, d, h - 0.03), "wood")  # body
    box(obj, f, (-0.01, 0.01, h - 0.035), (w + 0.01, d + 0.0, h), "wood")  # cornice
    for x0, x1, hx in ((0.003, w / 2 - 0.0015, w / 2 - 0.05), (w / 2 + 0.0015, w - 0.003, w / 2 + 0.05)):
        box(obj, f, (x0, 0.0, 0.085), (x1, 0.022, h - 0.04), "wood")  # door
        box(obj, f, (hx - 0.006, -0.03, 0.95), (hx + 0.006, -0.018, 1.15), "metal")  # handle bar
        for z in (0.98, 1.12):
            box(obj, f, (hx - 0.005, -0.02, z - 0.005), (hx + 0.005, 0.002, z + 0.005), "metal")


def waste_bin(obj, f):
    cylinder(obj, f, (0, 0, 0), 0.13, 0.0, 0.35, 12, "plastic")


def plant(obj, f, rng):
    """A pot with a few leaves (thin boxes turned about the stem)."""
    cylinder(obj, f, (0, 0, 0), 0.15, 0.0, 0.4, 12, "pot")
    cylinder(obj, f, (0, 0, 0), 0.012, 0.3, 0.9, 8, "leaf")  # stem
    for k in range(6):
        a = f.turned(k * 60 + rng.uniform(-15, 15))
        z = 0.55 + 0.06 * k
        box(obj, a, (0.005, -0.04, z), (0.28, 0.04, z + 0.008), "leaf")


def skirting(obj, f, length, cuts, height):
    """Skirting board along a wall face (frame f: x along the face, y into the room,
    the face at y = 0), from x = 0 to `length`, left out over the door intervals `cuts`
    (its ends 4 cm inside the door frames' jambs)."""
    x = 0.0
    pieces = []
    for a, b in sorted(cuts):
        pieces.append((x, a - 0.04))
        x = b + 0.04
    pieces.append((x, length))
    for x0, x1 in pieces:
        if x1 - x0 > 0.01:
            box(obj, f, (x0, -0.005, 0), (x1, 0.015, height), "skirting")


# --- the building ------------------------------------------------------------------------

def lamp_places(n):
    """Where an office's n lamps hang, as fractions of its width and depth: a row along
    its width for up to 3 lamps, else two rows (0.3 and 0.7 of the depth); each row's
    lamps spread evenly over 0.3 to 0.7 of the width (one lamp: the middle)."""
    rows = 1 if n <= 3 else 2
    places = []
    for r in range(rows):
        count = n // rows + (1 if r < n % rows else 0)
        v = 0.5 if rows == 1 else 0.3 + 0.4 * r
        for i in range(count):
            places.append((0.5 if count == 1 else 0.3 + 0.4 * i / (count - 1), v))
    return places


def build(nx, ny, storeys, seed, lamps=2):
    obj = Obj()
    rng = random.Random(seed)
    X, Y = nx * ROOM_X, ny * ROOM_Y
    ho, hi = OUTER / 2, INNER / 2
    e = ho - SLAB_IN  # slab edge beyond the outer wall axes
    luminaires, grids = [], []

    def win_x(i):  # the windows of office column i in a wall along x, as x ranges
        return [(i * ROOM_X + c - WIN_W / 2, i * ROOM_X + c + WIN_W / 2) for c in (1.4, 3.6)]

    def win_y(j):
        c = 2.5
        return [(j * ROOM_Y + c - WIN_W / 2, j * ROOM_Y + c + WIN_W / 2)]

    door_x = lambda i: (i * ROOM_X + DOOR_X, i * ROOM_X + DOOR_X + DOOR_W)  # in walls along x
    door_y = lambda j: (j * ROOM_Y + DOOR_Y, j * ROOM_Y + DOOR_Y + DOOR_W)  # in walls along y

    for k in range(storeys + 1):
        z = k * STOREY
        obj.element(f"IfcSlab_{k}" if k < storeys else "IfcRoof")
        box(obj, WORLD, (-e, -e, z - SLAB), (X + e, Y + e, z), "concrete",
            {"+z": "floor" if k < storeys else "roof", "-z": "ceiling" if k > 0 else "concrete"})

    for k in range(storeys):
        z = k * STOREY
        s = f"s{k + 1}"
        zw = (z - SLAB, z + STOREY)  # outer walls through both slabs
        window = lambda a, b: (a, b, z + SILL, z + SILL + WIN_H)
        # Outer walls: wall frames with x along the wall, y into the building, z absolute.
        outer = [
            ("south", Frame((-ho, 0, 0)), X + OUTER, [w for i in range(nx) for w in win_x(i)], ho),
            ("north", Frame((-ho, Y, 0), (1, 0, 0), (0, -1, 0)), X + OUTER, [w for i in range(nx) for w in win_x(i)], ho),
            ("west", Frame((0, 0, 0), (0, 1, 0), (1, 0, 0)), Y, [w for j in range(ny) for w in win_y(j)], 0.0),
            ("east", Frame((X, 0, 0), (0, 1, 0), (-1, 0, 0)), Y, [w for j in range(ny) for w in win_y(j)], 0.0),
        ]
        for name, f, length, wins, offset in outer:
            obj.element(f"IfcWall_{s}_{name}")
            wall(obj, f, length, -ho, ho, zw[0], zw[1], [window(a + offset, b + offset) for a, b in wins])
            obj.element(f"IfcWindow_{s}_{name}")
            for a, b in wins:
                window_frame(obj, f.moved(0, 0, z), a + offset, b + offset, SILL, SILL + WIN_H)
            obj.element(f"IfcFlowTerminal_{s}_{name}_radiators")
            for a, b in wins:
                radiator(obj, f.moved(0, 0, z), a + offset + 0.15, b + offset - 0.15)

        # Inner walls, the full length of the building, crossing each other.
        for j in range(1, ny):
            f = Frame((0, j * ROOM_Y, 0))
            obj.element(f"IfcWall_{s}_inner_y{j}")
            doors = [door_x(i) for i in range(nx)]
            wall(obj, f, X, -hi, hi, z, z + CLEAR, [(a, b, z, z + DOOR_H) for a, b in doors])
            obj.element(f"IfcDoor_{s}_inner_y{j}_frames")
            for a, b in doors:
                door_frame(obj, f.moved(0, 0, z), a, b)
        for i in range(1, nx):
            f = Frame((i * ROOM_X, 0, 0), (0, 1, 0), (1, 0, 0))
            obj.element(f"IfcWall_{s}_inner_x{i}")
            doors = [door_y(j) for j in range(ny)]
            wall(obj, f, Y, -hi, hi, z, z + CLEAR, [(a, b, z, z + DOOR_H) for a, b in doors])
            obj.element(f"IfcDoor_{s}_inner_x{i}_frames")
            for a, b in doors:
                door_frame(obj, f.moved(0, 0, z), a, b)

        # Offices.
        for j in range(ny):
            for i in range(nx):
                r = j * nx + i + 1
                room = f"{s}_r{r}"
                x0 = i * ROOM_X + (ho if i == 0 else hi)
                x1 = (i + 1) * ROOM_X - (ho if i == nx - 1 else hi)
                y0 = j * ROOM_Y + (ho if j == 0 else hi)
                y1 = (j + 1) * ROOM_Y - (ho if j == ny - 1 else hi)
                W, D = x1 - x0, y1 - y0
                F = Frame((x0, y0, z))  # the office's own frame: its south-west inner corner

                # Skirting: boards along x run 5 mm into the walls along y; boards along
                # y end inside them (and differ in height, so no edges meet).
                obj.element(f"IfcCovering_{room}_skirting")
                cut_x = [(a - x0 + 0.005, b - x0 + 0.005) for a, b in [door_x(i)]]
                skirting(obj, Frame((x0 - 0.005, y0, z)), W + 0.01, cut_x if j > 0 else [], 0.06)
                skirting(obj, Frame((x1 + 0.005, y1, z), (-1, 0, 0), (0, -1, 0)), W + 0.01,
                         [(W + 0.01 - b, W + 0.01 - a) for a, b in cut_x] if j < ny - 1 else [], 0.06)
                cut_y = [(a - y0 - 0.01, b - y0 - 0.01) for a, b in [door_y(j)]]
                fw = Frame((x0 + 0.001, y1 - 0.01, z), (0, -1, 0), (1, 0, 0))
                skirting(obj, fw, D - 0.02, [(D - 0.02 - b, D - 0.02 - a) for a, b in cut_y] if i > 0 else [], 0.065)
                fe = Frame((x1 - 0.001, y0 + 0.01, z), (0, 1, 0), (-1, 0, 0))
                skirting(obj, fe, D - 0.02, cut_y if i < nx - 1 else [], 0.065)

                # Two desks back to back in the middle, chairs on the outside.
                cu = W * 0.55 + rng.uniform(-0.08, 0.08)
                cv = D * 0.5 + rng.uniform(-0.05, 0.05)
                for side, (fy, turn) in enumerate(((cv - 0.02, 0), (cv + 0.02, 180))):
                    label = "ab"[side]
                    # Desk frame: origin at the desk's user-side left corner, y away from the user.
                    if turn == 0:
                        df = Frame(F(cu - 0.8, fy - 0.8, 0))
                    else:
                        df = Frame(F(cu + 0.8, fy + 0.8, 0), (-1, 0, 0), (0, -1, 0))
                    obj.element(f"IfcFurniture_{room}_desk_{label}")
                    desk(obj, df)
                    obj.element(f"IfcFurniture_{room}_pedestal_{label}")
                    pedestal(obj, df.moved(1.6 - 0.12 - 0.42, 0.1, 0))
                    obj.element(f"IfcFurniture_{room}_monitor_{label}")
                    monitor(obj, df.moved(0.8 + rng.uniform(-0.1, 0.1), 0.55, 0.74).turned(rng.uniform(-8, 8)))
                    keyboard(obj, df.moved(0.8 + rng.uniform(-0.08, 0.08), 0.22, 0.74).turned(rng.uniform(-6, 6)))
                    obj.element(f"IfcFurniture_{room}_chair_{label}")
                    chair(obj, df.moved(0.8 + rng.uniform(-0.2, 0.2), -rng.uniform(0.3, 0.45), 0)
                          .turned(rng.uniform(-25, 25)), rng)
                    obj.element(f"IfcFurniture_{room}_bin_{label}")
                    waste_bin(obj, df.moved(0.3, 0.4, 0))

                # Shelf against the east wall, cupboard against the west wall, both 2.5 cm off it.
                obj.element(f"IfcFurniture_{room}_shelf")
                shelf(obj, Frame(F(W - 0.025 - 0.35, 0.15 + rng.uniform(0, 0.05), 0), (0, 1, 0), (1, 0, 0)), rng)
                obj.element(f"IfcFurniture_{room}_cupboard")
                cupboard(obj, Frame(F(0.025 + 0.45, 0.15 + rng.uniform(0, 0.05) + 1.2, 0), (0, -1, 0), (-1, 0, 0)))
                if rng.random() < 0.6:
                    obj.element(f"IfcFurniture_{room}_plant")
                    plant(obj, F.moved(W - 0.3, D - 0.3, 0), rng)

                top = z + CLEAR - 0.2
                lumens = 6000 // lamps if 6000 % lamps == 0 else round(6000 / lamps, 3)
                for k, (u, v) in enumerate(lamp_places(lamps)):
                    luminaires.append({"type": "point", "lumens": lumens,
                                       "name": f"{room}_{chr(ord('a') + k)}",
                                       "position": [round(x0 + u * W, 4), round(y0 + v * D, 4), round(top, 4)]})
                grids.append({"name": room, "rectangle": [round(c, 4) for c in (x0, y0, x1, y1)],
                              "height": round(z + 0.8, 4), "border": 0.5})
    return obj, luminaires, grids


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out", metavar="OUT_PREFIX", help="writes OUT_PREFIX.obj, .mtl and .json")
    parser.add_argument("--storeys", type=int, required=True)
    parser.add_argument("--rooms", nargs=2, type=int, default=[6, 3], metavar=("NX", "NY"))
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--lamps", type=int, default=2, help="point luminaires per office, 6000 lm in all (default 2)")
    args = parser.parse_args()
    nx, ny = args.rooms
    if args.storeys < 1 or nx < 1 or ny < 1 or not 1 <= args.lamps <= 26:
        parser.error("--storeys and --rooms must be at least 1, --lamps 1 to 26")
    obj, luminaires, grids = build(nx, ny, args.storeys, args.seed, args.lamps)

    base = args.out[:-4] if args.out.endswith(".obj") else args.out
    name = os.path.basename(base)
    with open(base + ".mtl", "w") as f:
        f.write("# dynrad office building materials (make_office.py): Kd is linear reflectance\n")
        for material, kd in MATERIALS:
            f.write(f"newmtl {material}\nKd {kd[0]} {kd[1]} {kd[2]}\n\n")
    with open(base + ".obj", "w") as f:
        f.write(f"# dynrad office building (make_office.py): {args.storeys} storeys of {nx} x {ny} offices, "
                f"seed {args.seed}; metres, z up\n")
        f.write(f"mtllib {name}.mtl\n")
        f.write("".join("v %.6f %.6f %.6f\n" % p for p in obj.v))
        for group, faces in obj.groups:
            if not faces:
                continue
            f.write(f"g {group}\n")
            current = None
            lines = []
            for material, t in faces:
                if material != current:
                    lines.append(f"usemtl {material}\n")
                    current = material
                lines.append("f %d %d %d\n" % t)
            f.write("".join(lines))
    scene = {"meshes": [{"file": name + ".obj"}], "luminaires": luminaires, "grids": grids}
    with open(base + ".json", "w") as f:
        f.write("{\n  \"meshes\": " + json.dumps(scene["meshes"]) + ",\n  \"luminaires\": [\n")
        f.write(",\n".join("    " + json.dumps(l) for l in luminaires))
        f.write("\n  ],\n  \"grids\": [\n")
        f.write(",\n".join("    " + json.dumps(g) for g in grids))
        f.write("\n  ]\n}\n")
    print(f"{base}.obj: {args.storeys} storeys, {len(obj.v)} vertices, {obj.triangles()} triangles, "
          f"{obj.solids} solids in {sum(1 for _, faces in obj.groups if faces)} elements; "
          f"{len(luminaires)} luminaires, {len(grids)} grids")


if __name__ == "__main__":
    main()
