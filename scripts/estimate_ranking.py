#!/usr/bin/python3
"""How well a lit mesh's per-vertex `error` estimate ranks the measured error.

    scripts/estimate_ranking.py LIT.ply REFERENCE.txt

LIT.ply: an ASCII PLY from `dynrad solve MODEL -o LIT.ply --ascii` of the 1990 room or
its obstructed variant (samples/globillum_room*.obj). REFERENCE.txt: the path-traced
floor-and-ceiling grid in tests/data. At each grid point the lit value is interpolated
in the triangle that holds it (as `dynrad probe` does on a flat face), and the estimate
is the largest `error` of that triangle's corners. Prints the mean measured and
estimated errors, where the measured worst points rank by the estimate, and how many
points the estimate puts below their measured error. The four ceiling points on the
source's corners are left out, as in bench_defaults.
"""
import sys

import numpy as np


def read_ascii_ply(path):
    with open(path) as f:
        vertices = faces = 0
        names = []
        in_vertex = False
        while True:
            words = f.readline().split()
            if words[:1] == ["element"]:
                in_vertex = words[1] == "vertex"
                if in_vertex:
                    vertices = int(words[2])
                else:
                    faces = int(words[2])
            elif words[:1] == ["property"] and in_vertex:
                names.append(words[-1])
            elif words == ["end_header"]:
                break
        v = np.array([[float(x) for x in f.readline().split()] for _ in range(vertices)])
        t = np.array([[int(x) for x in f.readline().split()[1:4]] for _ in range(faces)])
    return v, t, names


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    v, t, names = read_ascii_ply(sys.argv[1])
    green, error = v[:, names.index("radiosity_g")], v[:, names.index("error")]
    rows = [line.split() for line in open(sys.argv[2]) if line[0] != "#"]
    rows = [r for r in rows
            if not (r[0] == "ceiling" and float(r[1]) in (4.75, 5.25) and float(r[2]) in (2.75, 3.25))]
    points = np.array([[float(x) for x in r[1:4]] for r in rows])
    reference = np.array([float(r[4]) for r in rows])
    value, estimate = np.full(len(rows), np.nan), np.zeros(len(rows))
    for height in (0.0, 3.0):
        flat = t[np.all(np.abs(v[t][:, :, 2] - height) < 1e-4, axis=1)]
        a, b, c = v[flat[:, 0], :2], v[flat[:, 1], :2], v[flat[:, 2], :2]
        e0, e1 = b - a, c - a
        det = e0[:, 0] * e1[:, 1] - e0[:, 1] * e1[:, 0]
        for i in np.where(np.abs(points[:, 2] - height) < 1e-6)[0]:
            d = points[i, :2] - a
            with np.errstate(divide="ignore", invalid="ignore"):
                u = (d[:, 0] * e1[:, 1] - d[:, 1] * e1[:, 0]) / det
                w = (e0[:, 0] * d[:, 1] - e0[:, 1] * d[:, 0]) / det
            inside = np.where((u >= -1e-9) & (w >= -1e-9) & (u + w <= 1 + 1e-9))[0]
            if len(inside) == 0:
                sys.exit(f"no triangle of {sys.argv[1]} holds {rows[i][0]} point {points[i]}")
            k = inside[0]
            value[i] = np.array([1 - u[k] - w[k], u[k], w[k]]) @ green[flat[k]]
            estimate[i] = error[flat[k]].max()
    measured = np.abs(value - reference) / reference
    by_measured = np.argsort(-measured)
    rank = np.empty(len(rows), dtype=int)
    rank[np.argsort(-estimate)] = np.arange(len(rows))
    print(f"{len(rows)} points: mean measured {100 * measured.mean():.3f}%, "
          f"mean estimated {100 * estimate.mean():.3f}%")
    print("measured worst 10: point, measured, estimated, the estimate's rank (0 = ranked worst)")
    for i in by_measured[:10]:
        print(f"  {rows[i][0]:8s} ({points[i, 0]:5.2f}, {points[i, 1]:5.2f}) "
              f"{100 * measured[i]:6.2f}% {100 * estimate[i]:8.2f}% {rank[i]:5d}")
    tenth = len(rows) // 10
    print(f"of the measured worst 10, in the estimate's worst tenth ({tenth} points): "
          f"{int(np.sum(rank[by_measured[:10]] < tenth))}")
    print(f"points whose estimate is below their measured error: {int(np.sum(estimate < measured))}")


if __name__ == "__main__":
    main()
