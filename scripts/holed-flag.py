#!/usr/bin/env python3
"""Writes presets/meshes/holed_flag.obj: a flag of 1.5 m x 1.0 m as triangles (each cell of a
48 x 32 grid split along alternating diagonals) with three round holes cut out, its texture
coordinates over the unit square, in metres with y up, its left edge at x = 0 from y = 1.0 m
to 2.0 m. Generated here, so the repository ships no third-party mesh.

    python3 scripts/holed-flag.py [OUT.obj]
"""
import math
import sys

COLS, ROWS = 48, 32
WIDTH, HEIGHT, TOP = 1.5, 1.0, 2.0
# (x, y, radius) [m]: the holes, away from the pole.
HOLES = [(0.95, 1.62, 0.11), (1.22, 1.30, 0.08), (0.62, 1.28, 0.09)]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "presets/meshes/holed_flag.obj"
    point = lambda c, r: (WIDTH * c / (COLS - 1), TOP - HEIGHT * r / (ROWS - 1))
    faces = []
    for r in range(ROWS - 1):
        for c in range(COLS - 1):
            a, b, d, e = (c, r), (c + 1, r), (c + 1, r + 1), (c, r + 1)
            # Counter-clockwise seen from +z: the front faces the viewer of the preset.
            tris = [(a, e, d), (a, d, b)] if (c + r) % 2 == 0 else [(a, e, b), (b, e, d)]
            for t in tris:
                cx = sum(point(*v)[0] for v in t) / 3
                cy = sum(point(*v)[1] for v in t) / 3
                if all(math.hypot(cx - x, cy - y) > rad for x, y, rad in HOLES):
                    faces.append(t)
    used = sorted({v for t in faces for v in t}, key=lambda v: (v[1], v[0]))
    index = {v: k + 1 for k, v in enumerate(used)}
    with open(out, "w") as f:
        f.write("# A flag with three holes: scripts/holed-flag.py writes it.\n")
        for c, r in used:
            x, y = point(c, r)
            f.write(f"v {x:.6f} {y:.6f} 0\n")
        for c, r in used:
            f.write(f"vt {c / (COLS - 1):.6f} {1 - r / (ROWS - 1):.6f}\n")
        for t in faces:
            f.write("f " + " ".join(f"{index[v]}/{index[v]}" for v in t) + "\n")
    print(f"{out}: {len(used)} vertices, {len(faces)} triangles")


if __name__ == "__main__":
    main()
