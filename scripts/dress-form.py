#!/usr/bin/env python3
"""Writes presets/meshes/dress_form.obj: a tailor's dress form (a torso from the hips to the
neck) as a closed surface of revolution with elliptical cross-sections, wound
counter-clockwise seen from outside, in metres with y up (its hips 0.80 m above the floor).
Generated here, so the repository ships no third-party mesh.

    python3 scripts/dress-form.py [OUT.obj]
"""
import math
import sys

# (height [m], half width along x [m], half depth along z [m]) from the bottom up.
PROFILE = [
    (0.80, 0.150, 0.120),
    (0.86, 0.175, 0.135),
    (0.93, 0.180, 0.140),
    (1.02, 0.140, 0.108),
    (1.10, 0.145, 0.115),
    (1.20, 0.170, 0.135),
    (1.30, 0.172, 0.120),
    (1.40, 0.185, 0.105),
    (1.46, 0.175, 0.090),
    (1.51, 0.110, 0.070),
    (1.54, 0.060, 0.055),
    (1.62, 0.055, 0.050),
]
SEGMENTS = 48


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "presets/meshes/dress_form.obj"
    lines = ["# A dress form, written by scripts/dress-form.py (metres, y up).", "o dress_form"]
    for y, rx, rz in PROFILE:
        for k in range(SEGMENTS):
            a = 2.0 * math.pi * k / SEGMENTS
            lines.append(f"v {rx * math.cos(a):.5f} {y:.5f} {rz * math.sin(a):.5f}")
    bottom = len(PROFILE) * SEGMENTS + 1
    top = bottom + 1
    lines.append(f"v 0 {PROFILE[0][0]:.5f} 0")
    lines.append(f"v 0 {PROFILE[-1][0]:.5f} 0")

    def at(ring, k):
        return ring * SEGMENTS + k % SEGMENTS + 1

    for ring in range(len(PROFILE) - 1):
        for k in range(SEGMENTS):
            # Seen from outside (angle growing from x towards z, y up) this quad winds
            # counter-clockwise as (ring, k), (ring + 1, k), (ring + 1, k + 1), (ring, k + 1).
            lines.append(f"f {at(ring, k)} {at(ring + 1, k)} {at(ring + 1, k + 1)} {at(ring, k + 1)}")
    last = len(PROFILE) - 1
    for k in range(SEGMENTS):
        lines.append(f"f {bottom} {at(0, k)} {at(0, k + 1)}")
        lines.append(f"f {top} {at(last, k + 1)} {at(last, k)}")
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
