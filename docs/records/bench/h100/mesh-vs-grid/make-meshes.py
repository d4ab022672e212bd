#!/usr/bin/env python3
"""Writes quads.obj and tris.obj beside this script: the 256 x 256 grid of grid.toml (1 cm apart,
top row at y = 2.6, hanging in the x-y plane) as a mesh of its quads, and of its quads each split
into two triangles along alternating diagonals (by the parity of column plus row), vertices in
the grid's order."""
import os
N, S = 256, 0.01
here = os.path.dirname(os.path.abspath(__file__))
verts = "".join(f"v {c * S:.6f} {2.6 - r * S:.6f} 0\n" for r in range(N) for c in range(N))
quads, tris = [], []
for r in range(N - 1):
    for c in range(N - 1):
        a = 1 + c + r * N
        quads.append(f"f {a} {a + N} {a + N + 1} {a + 1}\n")
        if (c + r) % 2 == 0:
            tris.append(f"f {a} {a + N} {a + N + 1}\nf {a} {a + N + 1} {a + 1}\n")
        else:
            tris.append(f"f {a} {a + N} {a + 1}\nf {a + 1} {a + N} {a + N + 1}\n")
for name, faces in [("quads.obj", quads), ("tris.obj", tris)]:
    with open(os.path.join(here, name), "w") as f:
        f.write(verts + "".join(faces))
