#!/usr/bin/env python3
"""Checks a recording (`simulate --record`) with the tools artists' pipelines use.

    pip install usd-core trimesh
    scripts/check-recording.py out.usda          # USD: Pixar's own reader and validators
    scripts/check-recording.py out.usdc          # the same converted to binary USD (docs/guide/recording.md)
    scripts/check-recording.py out_00010.obj     # one OBJ frame, read with trimesh
    scripts/check-recording.py out.glb           # glTF binary, read with trimesh (first frame)

USD: the stage opens, every validator usd-core registers passes (UsdValidation), and at every 10th time code each mesh's
faces are wound as its normals point (counter-clockwise seen from the side the normals face;
AGREE below),
its extent holds its points, and it has a UsdPreviewSurface material bound. OBJ: each `o`
group read as its own mesh: faces against normals; a watertight one (a rope, a sphere, a box)
has a positive volume, and spheres and boxes must be watertight. Prints a line per object and exits
1 when anything fails.
"""
import sys
import warnings

import numpy as np

# The share of faces whose winding must agree with their vertices' normals. Not all: a
# cloth's normals are averaged over its vertices' faces, and in a fold sharper than a grid cell
# a face can lie against them (0.1% of the crumpled towel's); a mesh wound inside out, as the
# ropes were, has nearly none.
AGREE = 0.95

warnings.filterwarnings("ignore", category=RuntimeWarning)  # trimesh's centre of an open sheet


def winding_agrees(points, normals, faces):
    """The fraction of faces whose winding agrees with the sum of their vertices' normals."""
    p = np.asarray(points, dtype=float)
    n = np.asarray(normals, dtype=float)
    f = np.asarray(faces, dtype=int)
    if len(f) == 0:
        return 1.0
    cross = np.cross(p[f[:, 1]] - p[f[:, 0]], p[f[:, 2]] - p[f[:, 0]])
    return float((np.einsum("ij,ij->i", cross, n[f].sum(axis=1)) > 0).mean())


def check_usd(path):
    from pxr import Usd, UsdGeom, UsdShade, UsdValidation

    failures = []
    stage = Usd.Stage.Open(path)
    validators = UsdValidation.ValidationRegistry().GetOrLoadAllValidators()
    for error in UsdValidation.ValidationContext(validators).Validate(stage):
        failures.append(f"validator {error.GetName()}: {error.GetMessage()}")
    start, end = int(stage.GetStartTimeCode()), int(stage.GetEndTimeCode())
    print(f"{path}: time codes {start}..{end} at {stage.GetFramesPerSecond()} frames/s")
    for prim in stage.Traverse():
        if not prim.IsA(UsdGeom.Gprim):
            continue
        material, _ = UsdShade.MaterialBindingAPI(prim).ComputeBoundMaterial()
        line = f"  {prim.GetPath()}: {prim.GetTypeName()}"
        if not material:
            failures.append(f"{prim.GetPath()}: no material bound")
        if prim.IsA(UsdGeom.Mesh):
            mesh = UsdGeom.Mesh(prim)
            counts = np.array(mesh.GetFaceVertexCountsAttr().Get())
            indices = np.array(mesh.GetFaceVertexIndicesAttr().Get())
            # Polygons as fans of triangles.
            starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
            faces = np.array([[indices[s], indices[s + k], indices[s + k + 1]]
                              for s, c in zip(starts, counts) for k in range(1, c - 1)])
            worst = 1.0
            for code in range(start, end + 1, 10):
                points = np.array(mesh.GetPointsAttr().Get(code))
                normals = mesh.GetNormalsAttr().Get(code)
                if normals is not None and len(normals) == len(points):
                    worst = min(worst, winding_agrees(points, np.array(normals), faces))
                extent = mesh.GetExtentAttr().Get(code)
                lo, hi = np.array(extent[0]), np.array(extent[1])
                if ((points < lo - 1e-6) | (points > hi + 1e-6)).any():
                    failures.append(f"{prim.GetPath()}: points outside the extent at {code}")
            if worst < AGREE:
                failures.append(f"{prim.GetPath()}: {100 * (1 - worst):.1f}% of faces wound against their normals")
            line += f", {len(faces)} triangles, faces agree with normals: {100 * worst:.1f}%"
        line += f", material {material.GetPath() if material else None}"
        print(line)
    return failures


def obj_groups(path):
    points, normals, groups = [], [], []
    with open(path) as f:
        for line in f:
            if line.startswith("o "):
                groups.append((line[2:].strip(), []))
            elif line.startswith("v "):
                points.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("vn "):
                normals.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("f "):
                groups[-1][1].append([int(c.split("/")[0]) - 1 for c in line.split()[1:]])
    return np.array(points), np.array(normals), groups


def check_obj(path):
    import trimesh

    failures = []
    points, normals, groups = obj_groups(path)
    print(f"{path}: {len(groups)} objects")
    for name, faces in groups:
        faces = np.array(faces)
        agree = winding_agrees(points, normals, faces)
        used = np.unique(faces)
        remap = np.zeros(len(points), dtype=int)
        remap[used] = np.arange(len(used))
        mesh = trimesh.Trimesh(points[used], remap[faces], process=False)
        mesh.merge_vertices()
        line = f"  {name}: {len(faces)} triangles, faces agree with normals: {100 * agree:.1f}%"
        if agree < AGREE:
            failures.append(f"{name}: {100 * (1 - agree):.1f}% of faces wound against their normals")
        if mesh.is_watertight:
            line += f", watertight, volume {mesh.volume:.6g} m^3"
            if mesh.volume <= 0:
                failures.append(f"{name}: inside out (volume {mesh.volume})")
        elif name.startswith(("collider_sphere", "collider_box")):
            failures.append(f"{name}: not closed")
        print(line)
    return failures


def check_gltf(path):
    import trimesh

    failures = []
    scene = trimesh.load(path, process=False)
    print(f"{path}: {len(scene.geometry)} meshes")
    for name, mesh in scene.geometry.items():
        normals = mesh.vertex_normals  # the file's, with process=False
        agree = winding_agrees(mesh.vertices, normals, mesh.faces)
        print(f"  {name}: {len(mesh.faces)} triangles, faces agree with normals: {100 * agree:.1f}%")
        if agree < AGREE:
            failures.append(f"{name}: {100 * (1 - agree):.1f}% of faces wound against their normals")
    return failures


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 2
    failures = []
    for path in sys.argv[1:]:
        if path.endswith((".usda", ".usdc", ".usd")):
            failures += check_usd(path)
        elif path.endswith(".glb"):
            failures += check_gltf(path)
        else:
            failures += check_obj(path)
    for f in failures:
        print(f"FAILED {f}")
    print("ok" if not failures else f"{len(failures)} problems")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
