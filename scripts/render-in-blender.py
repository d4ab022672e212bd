#!/usr/bin/env python3
"""Renders a USD recording in Blender (Cycles, on the CPU), as an artist would import it.

    pip install bpy==4.2.0          # Blender 4.2 as a Python module (Python 3.11)
    scripts/render-in-blender.py recording.usda picture.png [FRAME]
    scripts/render-in-blender.py recording.pc2 picture.png [FRAME]
    scripts/render-in-blender.py recording.glb picture.png [FRAME]

Imports the file with Blender's own USD importer (a `.pc2` recording: its OBJ meshes, each with
a Mesh Cache modifier reading its point cache, as a user would set them up), prints what came in (objects, their
materials and colours, the frame range), and renders FRAME (default: the last) at 640 x 400
with a sun and a camera looking at everything but the ground. docs/images/recording-in-blender.jpg
was made with it from `simulate --preset presets/tablecloth.toml --frames 90 --record`.
"""
import sys

import bpy
import mathutils


def import_point_caches(path):
    """A `.pc2` recording: the meshes from `STEM.obj` (Blender's OBJ importer keeps the file's
    Y-up coordinates in the mesh and turns the object to Z-up), each animated by its
    `STEM_NAME.pc2` through a Mesh Cache modifier (its default axes: the points as stored)."""
    import os
    import struct

    stem = path[: -len(".pc2")]  # the name given to --record, not one mesh's cache
    bpy.ops.wm.obj_import(filepath=stem + ".obj")
    scene = bpy.context.scene
    for o in bpy.data.objects:
        cache = f"{stem}_{o.name}.pc2"
        if o.type != "MESH" or not os.path.exists(cache):
            continue
        with open(cache, "rb") as f:
            _, _, points, start, _, samples = struct.unpack("<12siiffi", f.read(32))
        if points != len(o.data.vertices):
            raise SystemExit(f"{cache}: {points} points for {len(o.data.vertices)} vertices")
        # The OBJ's normals are the first frame's: shade from the cached points instead.
        if o.data.has_custom_normals:
            bpy.context.view_layer.objects.active = o
            bpy.ops.mesh.customdata_custom_splitnormals_clear()
        o.data.polygons.foreach_set("use_smooth", [True] * len(o.data.polygons))
        modifier = o.modifiers.new("msdsim", "MESH_CACHE")
        modifier.cache_format = "PC2"
        modifier.filepath = cache
        modifier.frame_start = start
        scene.frame_start, scene.frame_end = int(start), int(start) + samples - 1


def main(path, picture, frame=None):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    if path.endswith(".pc2"):
        import_point_caches(path)
    elif path.endswith(".glb"):
        # The importer turns the animation's seconds into frames at the scene's rate: the
        # presets' 60 frames/s, so that frame n is the recording's frame n.
        bpy.context.scene.render.fps = 60
        # Shading "SMOOTH": normals from the animated points (the file's are the first frame's
        # plus each target's, which Blender does not blend into its custom normals).
        bpy.ops.import_scene.gltf(filepath=path, import_shading="SMOOTH")
        ends = [a.frame_range[1] for a in bpy.data.actions]
        bpy.context.scene.frame_start, bpy.context.scene.frame_end = 0, int(max(ends, default=0))
    else:
        bpy.ops.wm.usd_import(filepath=path)
    scene = bpy.context.scene
    print(f"frames {scene.frame_start}..{scene.frame_end}")
    for o in bpy.data.objects:
        materials = [m.name for m in o.data.materials] if o.type == "MESH" else []
        print(f"  {o.name}: {o.type} {materials}")
    for m in bpy.data.materials:
        bsdf = m.node_tree.nodes.get("Principled BSDF") if m.node_tree else None
        if bsdf:
            print(f"  material {m.name}: base colour {tuple(round(c, 3) for c in bsdf.inputs['Base Color'].default_value)}")
    scene.frame_set(scene.frame_end if frame is None else frame)
    bpy.context.view_layer.update()
    # Everything but the ground, in Blender's Z-up world (the importer turns USD's Y-up).
    corners = [o.matrix_world @ mathutils.Vector(c) for o in bpy.data.objects
               if o.type == "MESH" and "ground" not in o.name for c in o.bound_box]
    lo = mathutils.Vector([min(c[k] for c in corners) for k in range(3)])
    hi = mathutils.Vector([max(c[k] for c in corners) for k in range(3)])
    centre, size = (lo + hi) / 2, (hi - lo).length
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(camera)
    scene.camera = camera
    camera.location = centre + mathutils.Vector((1.0, -1.0, 0.75)).normalized() * 1.6 * size
    camera.rotation_euler = (centre - camera.location).to_track_quat("-Z", "Y").to_euler()
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    sun.data.energy = 3.0
    sun.rotation_euler = (0.7, 0.3, 0.5)
    scene.collection.objects.link(sun)
    scene.world = bpy.data.worlds.new("world")
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 16
    scene.render.resolution_x, scene.render.resolution_y = 640, 400
    scene.render.filepath = picture
    bpy.ops.render.render(write_still=True)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        print(__doc__)
        sys.exit(2)
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]) if len(sys.argv) > 3 else None)
