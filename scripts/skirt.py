#!/usr/bin/env python3
"""Writes presets/meshes/skirt.obj: a flared skirt as two panels (front and back) of quads, each
half an elliptic cone around the dress form of scripts/dress-form.py, open at the sides by a
gap that the preset's seams close; texture coordinates as a sewing pattern, each panel its own
island in half of the unit square (front left, back right), u running left to right and v up as
seen from outside, so that a texture reads unmirrored and the UV winding is the faces'. Prints
the seams' vertex runs (1-based OBJ numbers less one: the preset's indices). Generated here, so
the repository ships no third-party mesh.

    python3 scripts/skirt.py [OUT.obj]
"""
import math
import sys

COLUMNS, ROWS = 22, 26   # vertices across a panel, and down it
GAP = 0.03               # radians left open at each side seam, each side of it
PAD = 0.02               # of a panel's half of the texture left empty at each side
# (height [m], half width along x [m], half depth along z [m]) from the waistband down.
PROFILE = [(1.00, 0.170, 0.135), (0.93, 0.205, 0.165), (0.45, 0.300, 0.260)]


def ring(y):
    for (y0, a0, b0), (y1, a1, b1) in zip(PROFILE, PROFILE[1:]):
        if y1 - 1e-9 <= y <= y0 + 1e-9:
            t = (y0 - y) / (y0 - y1)
            return a0 + t * (a1 - a0), b0 + t * (b1 - b0)
    raise ValueError(y)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "presets/meshes/skirt.obj"
    top, bottom = PROFILE[0][0], PROFILE[-1][0]
    vertices, uvs, faces, sides = [], [], [], []
    for panel in range(2):   # 0: front (z > 0), 1: back
        base = len(vertices)
        start = GAP + panel * math.pi
        for r in range(ROWS):
            y = top - (top - bottom) * r / (ROWS - 1)
            a, b = ring(y)
            for c in range(COLUMNS):
                angle = start + (math.pi - 2 * GAP) * c / (COLUMNS - 1)
                vertices.append((a * math.cos(angle), y, b * math.sin(angle)))
                # (c runs right to left seen from outside: u runs the other way)
                u = 1 - c / (COLUMNS - 1)
                uvs.append(((panel + PAD + (1 - 2 * PAD) * u) / 2, 1 - r / (ROWS - 1)))
        for r in range(ROWS - 1):
            for c in range(COLUMNS - 1):
                i = base + c + r * COLUMNS
                # Counter-clockwise seen from outside: the front faces out.
                faces.append((i, i + 1, i + 1 + COLUMNS, i + COLUMNS))
        sides.append(([base + r * COLUMNS for r in range(ROWS)],
                      [base + COLUMNS - 1 + r * COLUMNS for r in range(ROWS)]))
    with open(out, "w") as f:
        f.write("# A two-panel skirt for the dress form: scripts/skirt.py writes it.\n")
        for x, y, z in vertices:
            f.write(f"v {x:.6f} {y:.6f} {z:.6f}\n")
        for u, v in uvs:
            f.write(f"vt {u:.6f} {v:.6f}\n")
        for q in faces:
            f.write("f " + " ".join(f"{k + 1}/{k + 1}" for k in q) + "\n")
    (front_start, front_end), (back_start, back_end) = sides
    print(f"{out}: {len(vertices)} vertices, {len(faces)} quads")
    print(f"seam at +x: from = {front_start}\n            to = {back_end}")
    print(f"seam at -x: from = {front_end}\n            to = {back_start}")


if __name__ == "__main__":
    main()
