#!/usr/bin/env python3
"""Newton 1.8 side of the twist comparison: Newton's own `cloth_twist` example
(newton/examples/cloth/example_cloth_twist.py) rebuilt without a viewer and timed.

Scene as in the example: warp's square_cloth.usd (50 x 50 = 2500 vertices, 4802 triangles, 150 x 100 units)
scaled by 0.01 (1.5 m x 1.0 m), turned 90 deg about z (so it lies in the y-z plane), density 0.2 kg/m^2,
FEM cloth tri_ke = tri_ka = 1e3, tri_kd = 2e-4, edge_ke = 1e-3, edge_kd = 1e-2, no gravity.
The two short columns (50 vertices each, at y = -0.75 and y = +0.75) are made inactive and turned about
+y and -y at pi/3 rad/s (60 deg/s each, opposite ways) by a kernel that runs every substep (it keeps
the time in a device array, so it is part of the CUDA graph). SolverVBD: 10 substeps x 4 iterations,
self-contact on (margin 0.002 m, gap 0.0015 m, vertex/edge contact buffers 64/128),
soft_contact_ke 1e3, kd 0.1, mu 0.2, 60 fps. Each frame: CollisionPipeline.collide, solver.rebuild_bvh,
then 10 x (clear_forces, apply_rotation, solver.step, swap), exactly the example's simulate().

The example reads the mesh with pxr (usd-core) from warp/examples/assets; neither is on the lent machine,
so the mesh is embedded below (the exact float32 vertices and int32 indices that
newton.usd.get_mesh returned for /root/cloth/cloth, sha256 of the raw bytes checked at load).
With pxr and the asset present, --mesh usd reads it the example's way instead.

Timing as in ../shared/peer/bench_stack.py: one CUDA graph a frame, CUDA events around back-to-back
launches. Kernels are compiled on a throw-away instance (warm-up frames), then a fresh instance is
captured and timed from t = 0 for --frames frames (300 = the example's 5 s, its default num_frames).
An event is recorded between frames, so per-frame and per-100-frame figures come out too; the
mean is (last event - first event) / frames, as bench_stack.py computes it.

  PYTHONPATH=/tmp/nw/site python3 bench_twist.py                 # self-contact on, then off
  python3 bench_twist.py --device cpu --frames 3 --warmup 1      # smoke test (no graph)
Output: lines starting with RESULT (one JSON object each).
"""
import argparse
import base64
import hashlib
import json
import math
import os
import statistics
import time
import zlib

import numpy as np
import warp as wp

import newton
from newton import ParticleFlags

# --- kernels copied verbatim from example_cloth_twist.py ---------------------------------------------


@wp.kernel
def initialize_rotation(
    # input
    vertex_indices_to_rot: wp.array[wp.int32],
    pos: wp.array[wp.vec3],
    rot_centers: wp.array[wp.vec3],
    rot_axes: wp.array[wp.vec3],
    t: wp.array[float],
    # output
    roots: wp.array[wp.vec3],
    roots_to_ps: wp.array[wp.vec3],
):
    tid = wp.tid()
    v_index = vertex_indices_to_rot[wp.tid()]

    p = pos[v_index]
    rot_center = rot_centers[tid]
    rot_axis = rot_axes[tid]
    op = p - rot_center

    root = wp.dot(op, rot_axis) * rot_axis

    root_to_p = p - root

    roots[tid] = root
    roots_to_ps[tid] = root_to_p

    if tid == 0:
        t[0] = 0.0


@wp.kernel
def apply_rotation(
    # input
    vertex_indices_to_rot: wp.array[wp.int32],
    rot_axes: wp.array[wp.vec3],
    roots: wp.array[wp.vec3],
    roots_to_ps: wp.array[wp.vec3],
    t: wp.array[float],
    angular_velocity: float,
    dt: float,
    end_time: float,
    # output
    pos_0: wp.array[wp.vec3],
    pos_1: wp.array[wp.vec3],
):
    cur_t = t[0]
    if cur_t > end_time:
        return

    tid = wp.tid()
    v_index = vertex_indices_to_rot[wp.tid()]

    rot_axis = rot_axes[tid]

    ux = rot_axis[0]
    uy = rot_axis[1]
    uz = rot_axis[2]

    theta = cur_t * angular_velocity

    R = wp.mat33(
        wp.cos(theta) + ux * ux * (1.0 - wp.cos(theta)),
        ux * uy * (1.0 - wp.cos(theta)) - uz * wp.sin(theta),
        ux * uz * (1.0 - wp.cos(theta)) + uy * wp.sin(theta),
        uy * ux * (1.0 - wp.cos(theta)) + uz * wp.sin(theta),
        wp.cos(theta) + uy * uy * (1.0 - wp.cos(theta)),
        uy * uz * (1.0 - wp.cos(theta)) - ux * wp.sin(theta),
        uz * ux * (1.0 - wp.cos(theta)) - uy * wp.sin(theta),
        uz * uy * (1.0 - wp.cos(theta)) + ux * wp.sin(theta),
        wp.cos(theta) + uz * uz * (1.0 - wp.cos(theta)),
    )

    root = roots[tid]
    root_to_p = roots_to_ps[tid]
    root_to_p_rot = R * root_to_p
    p_rot = root + root_to_p_rot

    pos_0[v_index] = p_rot
    pos_1[v_index] = p_rot

    if tid == 0:
        t[0] = cur_t + dt


# --- the mesh: warp/examples/assets/square_cloth.usd, prim /root/cloth/cloth, via newton.usd.get_mesh --------
MESH_NV, MESH_NI = 2500, 14406
MESH_SHA256 = "cd5f388b57c98c5a77f3d5016d73df6cfbf8c499570e8511b830dbe8f8af6f6d"
MESH_B64 = """
eNpMnQWULdXVhHn+QggWgoaQEAghJLjb9Nm4u7u7u7u7u7u7u7u7u7s7/NS7X81frFWrZL2Zubd7r5rhdvc5I4107J0jjfhv/jvP
e/2wfr3oHQf062/P2KtfzzJkp369/72b9utn91uzX0+6wLL9equRF+zXdzw0R78e/ZBp+vWqi07ary8ebbx+/dPjo/TrBY4cqV9P
dd77d1g/PPnj/XqDi6/r10OmOq1fn3nFvv16l/VX7tfXbTJFv379na9vt1768yP79bgf3XVb6L74N118bRffs8XPavEaWry2Fq+5
xXtp8R5bvPeKY1JxrCqOYcWxrTjmFeei4hxVnLuKc1pxritmoGI2KmamX4800rGpR5yv6Z/t658rac+VtOdK2nMl7bmS9lxJe66k
PVfSnitpz5W050racyXtuZL2XEl7rqQ9V9KeK2nPlbTnStpzJe25kvZcSXuupD1X6L74N118bRffs8XPavEaWry2Fq+5xXtp8R5b
vPeKY1JxrCqOYcWxrTjmFeei4hxVnLuKc1pxritmoGI2KmamX3uu0CPO1/oXz9Q/V9KeK2nPlbTnStpzJe25kvZcSXuupD1X0p4r
ac+VtOdK2nMl7bmS9lxJe66kPVfSnitpz5W050racyXtuZL2XEl7rtB98W+6+NouvmeLn9XiNbR4bS1ec4v30uI9tnjvFcek4lhV
HMOKY1txzCvORcU5qjh3Fee04lxXzEDFbFTMTL/2XKFHnK9T9pyqf66kPVfSnitpz5W050racyXtuZL2XEl7rqQ9V9KeK2nPlbTn
StpzJe25kvZcSXuupD1X0p4rac+VtOdK2nMl7bmS9lyh++LfdPG1XXzPFj+rxWto8dpavOYW76XFe2zx3iuOScWxqjiGFce24phX
nIuKc1Rx7irOacW5rpiBitmomJl+7blCjzhfTyw/Wf9cSXuupD1X0p4rac+VtOdK2nMl7bmS9lxJe66kPVfSnitpz5W050racyXt
uZL2XEl7rqQ9V9KeK2nPlbTnStpzJe25QvfFv+nia7v4ni1+VovX0OK1tXjNLd5Li/fY4r1XHJOKY1VxDCuObcUxrzgXFeeo4txV
nNOKc10xAxWzUTEz/dpzhR5xvoZMNVH/XEl7rqQ9V9KeK2nPlbTnStpzJe25kvZcSXuupD1X0p4rac+VtOdK2nMl7bmS9lxJe66k
PVfSnitpz5W050racyXtuUL3xb/p4mu7+J4tflaL19DitbV4zS3eS4v32OK9VxyTimNVcQwrjm3FMa84FxXnqOLcVZzTinNdMQMV
s1ExM/3ac4Uecb5mGTJO/1xJe66kPVfSnitpz5W050racyXtuZL2XEl7rqQ9V9KeK2nPlbTnStpzJe25kvZcSXuupD1X0p4rac+V
tOdK2nMl7blC98W/6eJru/ieLX5Wi9fQ4rW1eM0t3kuL99jivVcck4pjVXEMK45txTGvOBcV56ji3FWc04pzXTEDFbNRMTP92nOF
HnG+Nn1p1P65kvZcSXuupD1X0p4rac+VtOdK2nMl7bmS9lxJe66kPVfSnitpz5W050racyXtuZL2XEl7rqQ9V9KeK2nPlbTnStpz
he6Lf9PF13bxPVv8rBavocVra/GaW7yXFu+xxXuvOCYVx6riGFYc24pjXnEuKs5RxbmrOKcV57piBipmo2Jm+rXnCj3ifJ15xdD+
uZL2XEl7rqQ9V9KeK2nPlbTnStpzJe25kvZcSXuupD1X0p4rac+VtOdK2nMl7bmS9lxJe66kPVfSnitpz5W050rac4Xui3/Txdd2
8T1b/KwWr6HFa2vxmlu8lxbvscV7rzgmFceq4hhWHNuKY15xLirOUcW5qzinFee6YgYqZqNiZvq15wo94nxdPNovd3iupD1X0p4r
ac+VtOdK2nMl7bmS9lxJe66kPVfSnitpz5W050racyXtuZL2XEl7rqQ9V9KeK2nPlbTnStpzJe25kvZcofvi33TxtV18zxY/q8Vr
aPHaWrzmFu+lxXts8d4rjknFsao4hhXHtuKYV5yLinNUce4qzmnFua6YgYrZqJiZfu25Qo84X3+5+eP+uZL2XEl7rqQ9V9KeK2nP
lbTnStpzJe25kvZcSXuupD1X0p4rac+VtOdK2nMl7bmS9lxJe66kPVfSnitpz5W050rac4Xui3/Txdd28T1b/KwWr6HFa2vxmlu8
lxbvscV7rzgmFceq4hhWHNuKY15xLirOUcW5qzinFee6YgYqZqNiZvq15wo94nztsv7L/XMl7bmS9lxJe66kPVfSnitpz5W050ra
cyXtuZL2XEl7rqQ9V9KeK2nPlbTnStpzJe25kvZcSXuupD1X0p4rac+VtOcK3Rf/pouv7eJ7tvhZLV5Di9fW4jW3eC8t3mOL915x
TCqOVcUxrDi2Fce84lxUnKOKc1dxTivOdcUMVMxGxcz0a88VesT5enesh/vnStpzJe25kvZcSXuupD1X0p4rac+VtOdK2nMl7bmS
9lxJe66kPVfSnitpz5W050racyXtuZL2XEl7rqQ9V9KeK2nPFbov/k0XX9vF92zxs1q8hhavrcVrbvFeWrzHFu+94phUHKuKY1hx
bCuOecW5qDhHFeeu4pxWnOuKGaiYjYqZ6deeK/SI87XoHTf1z5W050racyXtuZL2XEl7rqQ9V9KeK2nPlbTnStpzJe25kvZcSXuu
pD1X0p4rac+VtOdK2nMl7bmS9lxJe66kPVfSnit0X/ybLr62i+/Z4me1eA0tXluL19zivbR4jy3ee8UxqThWFcew4thWHPOKc1Fx
jirOXcU5rTjXFTNQMRsVM9OvPVfoEefruk0u6p8rac+VtOdK2nMl7bmS9lxJe66kPVfSnitpz5W050racyXtuZL2XEl7rqQ9V9Ke
K2nPlbTnStpzJe25kvZcSXuupD1X6L74N118bRffs8XPavEaWry2Fq+5xXtp8R5bvPeKY1JxrCqOYcWxrTjmFeei4hxVnLuKc1px
ritmoGI2KmamX3uu0CPO10Tjn9Q/V9KeK2nPlbTnStpzJe25kvZcSXuupD1X0p4rac+VtOdK2nMl7bmS9lxJe66kPVfSnitpz5W0
50racyXtuZL2XEl7rtB98W+6+NouvmeLn9XiNbR4bS1ec4v30uI9tnjvFcek4lhVHMOKY1txzCvORcU5qjh3Fee04lxXzEDFbFTM
TL/2XKFHnK/97z2wf66kPVfSnitpz5W050racyXtuZL2XEl7rqQ9V9KeK2nPlbTnStpzJe25kvZcSXuupD1X0p4rac+VtOdK2nMl
7bmS9lyh++LfdPG1XXzPFj+rxWto8dpavOYW76XFe2zx3iuOScWxqjiGFce24phXnIuKc1Rx7irOacW5rpiBitmomJl+7blCjzhf
r7+zdf9cSXuupD1X0p4rac+VtOdK2nMl7bmS9lxJe66kPVfSnitpz5W050racyXtuZL2XEl7rqQ9V9KeK2nPlbTnStpzJe25QvfF
v+nia7v4ni1+VovX0OK1tXjNLd5Li/fY4r1XHJOKY1VxDCuObcUxrzgXFeeo4txVnNOKc10xAxWzUTEz/dpzhR5xvq6cc+n+uZL2
XEl7rqQ9V9KeK2nPlbTnStpzJe25kvZcSXuupD1X0p4rac+VtOdK2nMl7bmS9lxJe66kPVfSnitpz5W050rac4Xui3/Txdd28T1b
/KwWr6HFa2vxmlu8lxbvscV7rzgmFceq4hhWHNuKY15xLirOUcW5qzinFee6YgYqZqNiZvq15wo94nztddx0/XMl7bmS9lxJe66k
PVfSnitpz5W050racyXtuZL2XEl7rqQ9V9KeK2nPlbTnStpzJe25kvZcSXuupD1X0p4rac+VtOcK3Rf/pouv7eJ7tvhZLV5Di9fW
4jW3eC8t3mOL915xTCqOVcUxrDi2Fce84lxUnKOKc1dxTivOdcUMVMxGxcz0a88VesT5WurzMfvnStpzJe25kvZcSXuupD1X0p4r
ac+VtOdK2nMl7bmS9lxJe66kPVfSnitpz5W050racyXtuZL2XEl7rqQ9V9KeK2nPFbov/k0XX9vF92zxs1q8hhavrcVrbvFeWrzH
Fu+94phUHKuKY1hxbCuOecW5qDhHFeeu4pxWnOuKGaiYjYqZ6deeK/SI87XAkW/f7rmS9lxJe66kPVfSnitpz5W050racyXtuZL2
XEl7rqQ9V9KeK2nPlbTnStpzJe25kvZcSXuupD1X0p4rac+VtOdK2nOF7ot/08XXdvE9W/ysFq+hxWtr8ZpbvJcW77HFe684JhXH
quIYVhzbimNecS4qzlHFuas4pxXnumIGKmajYmb6tecKPeJ8fTTXWf1zJe25kvZcSXuupD1X0p4rac+VtOdK2nMl7bmS9lxJe66k
PVfSnitpz5W050racyXtuZL2XEl7rqQ9V9KeK2nPlbTnCt0X/6aLr+3ie7b4WS1eQ4vX1uI1t3gvLd5ji/decUwqjlXFMaw4thXH
vOJcVJyjinNXcU4rznXFDFTMRsXM9GvPFXrE+Rr3o7n650racyXtuZL2XEl7rqQ9V9KeK2nPlbTnStpzJe25kvZcSXuupD1X0p4r
ac+VtOdK2nMl7bmS9lxJe66kPVfSnitpzxW6L/5NF1/bxfds8bNavIYWr63Fa27xXlq8xxbvveKYVByrimNYcWwrjnnFuag4RxXn
ruKcVpzrihmomI2KmenXniv0iPN108l73ua5kvZcSXuupD1X0p4rac+VtOdK2nMl7bmS9lxJe66kPVfSnitpz5W050racyXtuZL2
XEl7rqQ9V9KeK2nPlbTnStpzhe6Lf9PF13bxPVv8rBavocVra/GaW7yXFu+xxXuvOCYVx6riGFYc24pjXnEuKs5RxbmrOKcV57pi
Bipmo2Jm+rXnCu3z1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz
1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz1Rdz
1Rdz1Rdz1Rdz1Re/B7v4PdjF78Eufg928Xuwi9+DXfwe7OL3YBe/B7v4PdjF78Eufg928Xuwi9+DXfwe7OL3YBe/B7v4PdjF78Eu
fg928Xuwi9+DXfwe7OL3YBe/B7v4PdjF78Eufg928Xuwi9+DXfwe7OL3YBe/B7v4PdjF78Eufg928Xuwi9+DXfwe7OL3YBe/B7v4
PdjF78Eufg928Xuwi9+DXfwe7OL3YBe/B7v4PdjF3+1d/N3exd/tXfzd3sXf7V383d7F3+1d/N3exd/tXfzd3sXf7V383d7F3+1d
/N3exd/tXfzd3sXf7V383d7F3+1d/N3exd/tXfzd3sXf7V383d7F3+1d/N3exd/tXfzd3sXf7V383d7F3+1d/N3exd/tXfzd3sXf
7V383d7F3+1d/N3exd/tXfzd3sXf7V383d7F3+1d/N3exd/tXfzd3sXf7V383d7F3+1d/N3execMXXzO0MXnDF18ztDF5wxdfM7Q
xecMXXzO0MXnDF18ztDF5wxdfM7QxecMXXzO0MXnDF18ztDF5wxdfM7QxecMXXzO0MXnDF18ztDF5wxdfM7QxecMXXzO0MXnDF18
ztDF5wxdfM7QxecMXXzO0MXnDF18ztDF5wxdfM7QxecMXXzO0MXnDF18ztDF5wxdfM7QxecMXXzO0MXnDF18ztDF5wxdfM7QxecM
XXzO0MXnoi0+F23xuWiLz0VbfC7a4nPRFp+LtvhctMXnoi0+F23xuWiLz0VbfC7a4nPRFp+LtvhctMXnoi0+F23xuWiLz0VbfC7a
4nPRFp+LtvhctMXnoi0+F23xuWiLz0VbfC7a4nPRFp+LtvhctMXnoi0+F23xuWiLz0VbfC7a4nPRFp+LtvhctMXnoi0+F23xuWiL
z0VbfC7a4nPRFp+LtvhctMXnoi0+F21xHafFdZwW13FaXMdpcR2nxXWcFtdxWlzHaXEdp8V1nBbXcVpcx2lxHafFdZwW13FaXMdp
cR2nxXWcFtdxWlzHaXEdp8V1nBbXcVpcx2lxHafFdZwW13FaXMdpcR2nxXWcFtdxWlzHaXEdp8V1nBbXcVpcx2lxHafFdZwW13Fa
XMdpcR2nxXWcFtdxWlzHaXEdp8V1nBbXcVpcx2lxHafFdZwW151bXHducd25xXXnFtedW1x3bnHducV15xbXnVtcd25x3bnFdecW
151bXHducd25xXXnFtedW1x3bnHducV15xbXnVtcd25x3bnFdecW151bXHducd25xXXnFtedW1x3bnHducV15xbXnVtcd25x3bnF
decW151bXHducd25xXXnFtedW1x3bnHducV15xbXnVtcd25x3bnFdecW151bXHducZ9Mi/tkWtwn0+I+mRb3ybS4T6bFfTIt7pNp
cZ9Mi/tkWtwn0+I+mRb3ybS4T6bFfTIt7pNpcZ9Mi/tkWtwn0+I+mRb3ybS4T6bFfTIt7pNpcZ9Mi/tkWtwn0+I+mRb3ybS4T6bF
fTIt7pNpcZ9Mi/tkWtwn0+I+mRb3ybS4T6bFfTIt7pNpcZ9Mi/tkWtwn0+I+mRb3ybS4T6bFfTIt7pNpcZ9Mi/tkWtzX1+K+vhb3
9bW4r6/FfX0t7utrcV9fi/v6WtzX1+K+vhb39bW4r6/FfX0t7utrcV9fi/v6WtzX1+K+vhb39bW4r6/FfX0t7utrcV9fi/v6WtzX
1+K+vhb39bW4r6/FfX0t7utrcV9fi/v6WtzX1+K+vhb39bW4r6/FfX0t7utrcV9fi/v6WtzX1+K+vhb39bW4r6/FfX0t7utrcV9f
i/v6WtzX1+K+vhb3Ibe4D7nFfcgt7kNucR9yi/uQW9yH3OI+5Bb3Ibe4D7nFfcgt7kNucR9yi/uQW9yH3OI+5Bb3Ibe4D7nFfcgt
7kNucR9yi/uQW9yH3OI+5Bb3Ibe4D7nFfcgt7kNucR9yi/uQW9yH3OI+5Bb3Ibe4D7nFfcgt7kNucR9yi/uQW9yH3OI+5Bb3Ibe4
D7nFfcgt7kNucR9yi/uQW9yH3OI+5Bb3Ibe4D7nFcxMtnpto8dxEi+cmWjw30eK5iRbPTbR4bqLFcxMtnpto8dxEi+cmWjw30eK5
iRbPTbR4bqLFcxMtnpto8dxEi+cmWjw30eK5iRbPTbR4bqLFcxMtnpto8dxEi+cmWjw30eK5iRbPTbR4bqLFcxMtnpto8dxEi+cm
Wjw30eK5iRbPTbR4bqLFcxMtnpto8dxEi+cmWjw30eK5iRbPTbR4bqLFcxMtnpto8ZxXi+e8Wjzn1eI5rxbPebV4zqvFc14tnvNq
8ZxXi+e8Wjzn1eI5rxbPebV4zqvFc14tnvNq8ZxXi+e8Wjzn1eI5rxbPebV4zqvFc14tnvNq8ZxXi+e8Wjzn1eI5rxbPebV4zqvF
c14tnvNq8ZxXi+e8Wjzn1eI5rxbPebV4zqvFc14tnvNq8ZxXi+e8Wjzn1eI5rxbPebV4zqvFc14tnvNq8ZxXi+e8WjyX2uK51BbP
pbZ4LrXFc6ktnktt8Vxqi+dSWzyX2uK51BbPpbZ4LrXFc6ktnktt8Vxqi+dSWzyX2uK51BbPpbZ4LrXFc6ktnktt8Vxqi+dSWzyX
2uK51BbPpbZ4LrXFc6ktnktt8Vxqi+dSWzyX2uK51BbPpbZ4LrXFc6ktnktt8Vxqi+dSWzyX2uK51BbPpbZ4LrXFc6ktnktt8Vxq
i+dSWzyX2uK51BbP0bd4jr7Fc/QtnqNv8Rx9i+foWzxH3+I5+hbP0bd4jr7Fc/QtnqNv8Rx9i+foWzxH3+I5+hbP0bd4jr7Fc/Qt
nqNv8Rx9i+foWzxH3+I5+hbP0bd4jr7Fc/QtnqNv8Rx9i+foWzxH3+I5+hbP0bd4jr7Fc/QtnqNv8Rx9i+foWzxH3+I5+hbP0bd4
jr7Fc/QtnqNv8Rx9i+foWzxH3+I5+hbP0bd4jr7Fuh8t1v1ose5Hi3U/Wqz70WLdjxbrfrRY96PFuh8t1v1ose5Hi3U/Wqz70WLd
jxbrfrRY96PFuh8t1v1ose5Hi3U/Wqz70WLdjxbrfrRY96PFuh8t1v1ose5Hi3U/Wqz70WLdjxbrfrRY96PFuh8t1v1ose5Hi3U/
Wqz70WLdjxbrfrRY96PFuh8t1v1ose5Hi3U/Wqz70WLdjxbrfrRY96PFuh8t1v1osU5Ri3WKWqxT1GKdohbrFLVYp6jFOkUt1ilq
sU5Ri3WKWqxT1GKdohbrFLVYp6jFOkUt1ilqsU5Ri3WKWqxT1GKdohbrFLVYp6jFOkUt1ilqsU5Ri3WKWqxT1GKdohbrFLVYp6jF
OkUt1ilqsU5Ri3WKWqxT1GKdohbrFLVYp6jFOkUt1ilqsU5Ri3WKWqxT1GKdohbrFLVYp6jFOkUt1ilqsU5Ri3WKWqyrVrGuWsW6
ahXrqlWsq1axrlrFumoV66pVrKtWsa5axbpqFeuqVayrVrGuWsW6ahXrqlWsq1axrlrFumoV66pVrKtWsa5axbpqFeuqVayrVrGu
WsW6ahXrqlWsq1axrlrFumoV66pVrKtWsa5axbpqFeuqVayrVrGuWsW6ahXrqlWsq1axrlrFumoV66pVrKtWsa5axbpqFeuqVayr
VrGuWsU6kBXrQFasA1mxDmTFOpAV60BWrANZsQ5kxTqQFetAVqwDWbEOZMU6kBXrQFasA1mxDmTFOpAV60BWrANZsQ5kxTqQFetA
VqwDWbEOZMU6kBXrQFasA1mxDmTFOpAV60BWrANZsQ5kxTqQFetAVqwDWbEOZMU6kBXrQFasA1mxDmTFOpAV60BWrANZsQ5kxTqQ
FetAVqwDWbEOZMU6kBXrQFasW1uxbm3FurUV69ZWrFtbsW5txbq1FevWVqxbW7FubcW6tRXr1lasW1uxbm3FurUV69ZWrFtbsW5t
xbq1FevWVqxbW7FubcW6tRXr1lasW1uxbm3FurUV69ZWrFtbsW5txbq1FevWVqxbW7FubcW6tRXr1lasW1uxbm3FurUV69ZWrFtb
sW5txbq1FevWVqxbW7FubcW6tRXr1lasW1uxbm3FOtsV62xXrLNdsc52xTrbFetsV6yzXbHOdsU62xXrbFess12xznbFOtsV62xX
rLNdsc52xTrbFetsV6yzXbHOdsU62xXrbFess12xznbFOtsV62xXrLNdsc52xTrbFetsV6yzXbHOdsU62xXrbFess12xznbFOtsV
62xXrLNdsc52xTrbFetsV6yzXbHOdsU62xXrbFess12xznbFOtsV62xX7AtQsS9Axb4AFfsCVOwLULEvQMW+ABX7AlTsC1CxL0DF
vgAV+wJU7AtQsS9Axb4AFfsCVOwLULEvQMW+ABX7AlTsC1CxL0DFvgAV+wJU7AtQsS9Axb4AFfsCVOwLULEvQMW+ABX7AlTsC1Cx
L0DFvgAV+wJU7AtQsS9Axb4AFfsCVOwLULEvQMW+ABX7AlTsC1CxL0DFvgAV+wJU7AtQsS9AxT4mFfuYVOxjUrGPScU+JhX7mFTs
Y1Kxj0nFPiYV+5hU7GNSsY9JxT4mFfuYVOxjUrGPScU+JhX7mFTsY1Kxj0nFPiYV+5hU7GNSsY9JxT4mFfuYVOxjUrGPScU+JhX7
mFTsY1Kxj0nFPiYV+5hU7GNSsY9JxT4mFfuYVOxjUrGPScU+JhX7mFTsY1Kxj0nFPiYV+5hU7GNSsY9JxT4mFfuYVOy7VLHvUsW+
SxX7LlXsu1Sx71LFvksV+y5V7LtUse9Sxb5LFfsuVey7VLHvUsW+SxX7LlXsu1Sx71LFvksV+y5V7LtUse9Sxb5LFfsuVey7VLHv
UsW+SxX7LlXsu1Sx71LFvksV+y5V7LtUse9Sxb5LFfsuVey7VLHvUsW+SxX7LlXsu1Sx71LFvksV+y5V7LtUse9Sxb5LFfsuVey7
VLHvUsU+cRX7xFXsE1exT1zFPnEV+8RV7BNXsU9cxT5xFfvEVewTV7FPXMU+cRX7xFXsE1exT1zFPnEV+8RV7BNXsU9cxT5xFfvE
VewTV7FPXMU+cRX7xFXsE1exT1zFPnEV+8RV7BNXsU9cxT5xFfvEVewTV7FPXMU+cRX7xFXsE1exT1zFPnEV+8RV7BNXsU9cxT5x
FfvEVewTV7FPXMU+cRX7xPXP1UgjzV+xr2XFvpYV+1pW7GtZsa9lxb6WFftaVuxrWbGvZcW+lhX7Wlbsa1mxr2XFvpYV+1pW7GtZ
sa9lxb6WFftaVuxrWbGvZcW+lhX7Wlbsa1mxr2XFvpYV+1pW7GtZsa9lxb6WFftaVuxrWbGvZcW+lhX7Wlbsa1mxr2XFvpYV+1pW
7GtZsa9lxb6WFftaVuxrWbGvZcW+lhX7Wlbsa1mxr+UInu53DOgFI00bXjwQnh4tzPA7BqGnDy8eDM+IFmbS/yOgZwwvHgrPjBZm
+R3D0DOHFw+HZ0ULs/2OP6BnDS8eGZ4dLczxO/6Inj28eBR4TrSgYfoTes7w4lHhDi1oIEZDd+HFo8OFFub6HWOgK7x4THhutDDP
7/gzeu7w4rHgedHCfLq2gp43vHhseH60sMDvGAc9f3jxuPCCaGGh3zEeesHw4vHhhdHCIr9jAvTC4cV/hRdFC4v9jgnRi4YX/w1e
HC0soXvA0IuHF/8dXhItLPU7/oFeMrx4YnhptLDM7/gneunw4kngZdHCcr9jUvSy4cX/gpdHCyv8jsnQy4cX/xteES2s9DsmR68Y
XvwfeGW0sMrvmAK9cnjxf+FV0cJqv+N/6FXDi6eEV0cLa/yOqdCrhxdPDa+JFtb6HdOg18Srh9ame8TroIV16Z3pyO3XpXvE66GF
9emdGcjt16d7xBughQ3pnZnI7Teke8QboYWN6Z1ZyO03pnvEm6CFTemd2cjtN6V7xJuhhc3pnTnI7Tene8RboIUt6Z0+cvst6R7x
Vmhha3qnkdtvTfeIt0EL29I7c5Hbb0v3iLdDC9vTO/OQ229P94h3QAs70jvzkdvvSPeId0ILO9M7C5Db70z3iHdBC7vSOwuR2+9K
94h3Qwu70zuLkNvvTveI90ALe9I7i5Hb70n3iPdCC3vTO0uQ2+9N94j3QQv70jtLkdvvS/eI90ML+9M7y5Db70/3iA9ACwfSO8uR
2x9I94gPQgsH0zsrkNsfTPeID0ELh9I7K5HbH0r3iA9DC4fTO6uQ2x9O94iPQAtH0jurkdsfSfeIj0ILR9M7a5DbH00XiY9Bq4uO
o3ekjw1/HN0jPh4tnEDvrEtufwLdIz4RLZxE76xPbn8S3SM+GS2cQu9sSG5/Ct0jPhUtnEbvbExufxrdIz4dLZxB72xKbn8G3SM+
Ey2cRe9sTm5/Ft0jPhstnEPvbElufw7dIz4XLZxH72xNbn8e3SM+Hy1cQO9sS25/Ad0jvhAtXETvbE9ufxHdI74YLVxC7+xIbn8J
3SO+FC1cRu/sTG5/Gd0jvhwtXEHv7EpufwXdI74SLVxF7+xObn8V3SO+Gi1cQ+/sSW5/Dd0jvhYtXEfv7E1ufx3dI74eLdxA7+xL
bn8D3SO+ES3cRO/sT25/E90jvhkt3ELvHEhufwvdI74VLdxG7xxMbn8b3SO+HS3cQe8cSm5/B90jvhMt3EXvHE5ufxfdI74bLdxD
7xxJbn8P3SO+Fy3cRx8dTX4fPXQ/3SN+AC08SO8cR27/IN0jfggtPEzvnEBu/zDdI34ELTxK75xEbv8o3SN+DC08Tu+cQm7/ON0j
fgItPEnvnEZu/yTdI34KLTxN75xBbv803SN+Bi08S++cRW7/LN0jfg4tPE/vnENu/zzdI34BLbxI75xHbv8i3SN+CS28TO9cQG7/
Mt0jfgUtvErvXERu/yrdI34NLbxO71xCbv863SN+Ay28Se9cRm7/Jt0jfgstvE3vXEFu/zbdI34HLbxL71xFbv8u3SN+Dy28T+9c
Q27/Pt0j/gAtfEjvXEdu/yHdI/4ILXxM79xAbv8x3SP+BC18Su/cRG7/Kd0j/gwtfE7v3EJu/zndI/4CLXxJ79xGbv8l3SP+Ci18
Te/cQW7/Nd0j/gYtfEvv3EVu/y3dI/4OLXxP79xDbv89XST+Aa0u+onekf4x/E90j/hntPALvfMguf0vdI/4V7TwG73zMLn9b3SP
WB9oPYofMKDXO4+S24sfhweihUEDer0jrdxe/CQ8GC0MGdDrHWnl9uKn4aFoYdiAXu9IK7cXPwsPRwt/GNDrHWnl9uLn4ZHRwh8H
9HpHWrm9+EV4FLTwpwG93pFWbi9+GR4VLYw2oNc70srtxa/Co6OFMQb0ekdaub34dXhMtPDnAb3ekVZuL34THgst/GVAr3eklduL
34bHRgvjDOj1jrRye/G78LhoYbwBvd6RVm4vfh8eHy1MMKDXO9LK7cUfwn9FCxMO6PWOtHJ78cfw39DCRAN6vSOt3F78Kfx3tPCP
Ab3ekVZuL/4cnhgt/HNAr3eklduLv4QnQQuTDuj1jrRye/HX8L/QwmQDer0jrdxe/C38b7Qw+YBe70grtxd/D/8HLUwxoNdH0srl
1UP/HdDrHvH/0MKUA3q9I63cXvwLPBVamHpAr3eklduLf4OnQQvTDuj1jrRy+2npIvF0aGF6+mgAuf30dJF4BrQwI300iNx+RrpI
PBNamJk+GkJuPzNdJJ4FLcxKHw0jt5+VLhLPhhZmp4/+QG4/O10kngMtzEkf/ZHcfk66SNyHFjr66E/k9h1dJG5ooeij0cjtiy4S
z4UW5qaPxiC3n5suEs+DFualj/5Mbj8vXSSeDy3MTx/9hdx+frpIvABaWJA+GofcfkG6SLwQWliYPhqP3H5huki8CFpYlD6agNx+
UbpIvBhaWJw+mpDcfnG6SLwEWliSPpqI3H5Juki8FFpYmj76B7n90nSReBm0sCx99E9y+2XpIvFyaGF5+mhScvvl6SLxCmhhRfpo
MnL7Feki8UpoYWX6aHJy+5XpIvEqaHXRavSR9KrhV6OLxKujhTXooynJ7degi8RrooW16KOpye3XonvEa6OFdeidacnt16F7xOui
hfXonenJ7deje8Tro4UN6J0Zye03oHvEG6KFjeidmcntN6J7xBujhU3onVnJ7Tehe8SbooXN6J3Zye03o3vEm6OFLeidOcntt6B7
xFuiha3onY7cfiu6R7w1WtiG3ily+23oHvG2aGE7emducvvt6B7x9mhhB3pnXnL7Hege8Y5oYSd6Z35y+53oHvHOaGEXemdBcvtd
6B7xrmhhN3pnYXL73ege8e5oYQ96Z1Fy+z3oHvGeaGEvemdxcvu96B7x3mhhH3pnSXL7fege8b5oYT96Z2ly+/3oHvH+aOEAemdZ
cvsD6B7xgWjhIHpneXL7g+ge8cFo4RB6Z0Vy+0PoHvGhaOEw+mhl8sPoocPpHvERaOFIemc1cvsj6R7xUWjhaHpnDXL7o+ke8TFo
4Vh6Zy1y+2PpHvFxaOF4emcdcvvj6R7xCWjhRHpnPXL7E+ke8Ulo4WR6ZwNy+5PpHvEpaOFUemcjcvtT6R7xaWjhdHpnE3L70+ke
8Rlo4Ux6ZzNy+zPpHvFZaOFsemcLcvuz6R7xOWjhXHpnK3L7c+ke8Xlo4Xx6Zxty+/PpHvEFaOFCemc7cvsL6R7xRWjhYnpnB3L7
i+ke8SVo4VJ6Zydy+0vpHvFlaOFyemcXcvvL6R7xFWjhSnpnN3L7K+ke8VVo4Wp6Zw9y+6vpHvE1aOFaemcvcvtr6R7xdWjhenpn
H3L76+ke8Q1o4UZ6Zz9y+xvpHvFNaOFmeucAcvub6R7xLWjhVnrnIHL7W+ke8W1o4XZ65xBy+9vpIvEdaHXRXfSO9J3h76J7xHej
hXvonSPJ7e+he8T3ooX76J2jye3vo3vE96OFB+idY8ntH6B7xA+ihYfonePJ7R+ie8QPo4VH6J0Tye0foXvEj6KFx+idk8ntH6N7
xI+jhSfonVPJ7Z+ge8RPooWn6J3Tye2fonvET6OFZ+idM8ntn6F7xM+ihefonbPJ7Z+je8TPo4UX6J1zye1foHvEL6KFl+id88nt
X6J7xC+jhVfonQvJ7V+he8SvooXX6J2Lye1fo3vEr6OFN+idS8nt36B7xG+ihbfoncvJ7d+ie8Rvo4V36J0rye3foXvE76KF9+id
q8nt36N7xO+jhQ/onWvJ7T+ge8QfooWP6J3rye0/onvEH6OFT+idG8ntP6F7xJ+ihc/onZvJ7T+je8Sfo4Uv6J1bye2/oHvEX6KF
r+ij28m/ooe+pnvE36CFb+mdu8jtv6V7xN+hhe/pnXvI7b+ne8Q/oIUf6Z37yO1/pHvEP6GFn+mdB8jtf6Z7xL+ghV/pnYfI7X+l
e8S/oQXdKPoo+rfw4sfgAWhh4MBe70grtxc/AQ9CC4MH9npHWrm9+Cl4CFoYOrDXO9LK7cXPwMPQwvCBvd6RVm4vfg7+A1oYeWCv
d6SV24tfgP+IFkYZ2OsdaeX24pfgP6GFUQf2ekdaub34FXg0tDD6wF7vSCu3F78Gj4EWxhzY6x1p5fbiN+A/o4WxBvZ6R1q5vfgt
+C9oYeyBvd6RVm4vfgceBy2MO7DXO9LK7cXvweOhhfEH9npHWrm9+AN4ArTw14G93pFWbi/+CJ4QLfxtYK93pJXbiz+BJ0ILfx/Y
6x1p5fbiz+B/oIWJB/Z6R1q5vfgL+J9oYZKBvd6RVm4v/gqeFK0ummxgr3ek/zXw/734W/jfaGHygb3ekVZuL/4e/g9amGJgr3ek
lduLf4T/ixb+N7DXO9LK7cU/w1OihakG9npHWrm9+Fd4arQwzcBe70grt5+GG9rF0w78/xvcp6OPRiK3n44uEk+PFmagjwaS289A
F4lnRAsz0UeDye1noovEM6OFWeijoeT2s9BF4lnRwmz00XBy+9noIvHsaGEO+mhkcvs56CLxnGihjz4ahdy+jy4Sd2ih0Uejkts3
ukhcaGEu+mh0cvu56CLx3GhhHvpoTHL7eegi8bxoYT76aCxy+/noIvH8aGEB+mhscvsF6CLxgmhhIfpoXHL7hegi8cJoYRH6aHxy
+0XoIvGiaGEx+uiv5PaL0UXixdHCEvTR38jtl6CLxEuihaXoo7+T2y9FF4mXRgvL0EcTk9svQxeJl0ULy9FHk5DLq4eWp4vEK6CF
FemjycjtV6SLxCuhhZXpo8nJ7Vemi8SroIVV6aMpyO1XpYvEq6GF1emj/5Hbr04XiddAC2vSR1OR269J94jXQgtr0zvTkNuvTfeI
10EL69I705Hbr0v3iNdDC+vTOzOQ269P94g3QAsb0jszkdtvSPeIN0ILG9M7s5Dbb0z3iDdBC5vSO7OR229K94g3Qwub0ztzkNtv
TveIt0ALW9I7feT2W9I94q3Qwtb0TiO335ruEW+DFrald+Yit9+W7hFvhxa2p3fmIbffnu4R74AWdqR35iO335HuEe+EFnamdxYg
t9+Z7hHvghZ2pXcWIrffle4R74YWdqd3FiG3353uEe+BFvakdxYjt9+T7hHvhRb2pneWILffm+4R74MW9qV3liK335fuEe+HFvan
d5Yht9+fLhIfgFYXHUTvSB8Y/iC6R3wwWjiE3lmR3P4Qukd8KFo4jN5Zmdz+MLpHfDhaOILeWZXc/gi6R3wkWjiK3lmd3P4oukd8
NFo4ht5Zk9z+GLpHfCxaOI7eWZvc/ji6R3w8WjiB3lmX3P4Eukd8Ilo4id5Zn9z+JLpHfDJaOIXe2ZDc/hS6R3wqWjiN3tmY3P40
ukd8Olo4g97ZlNz+DLpHfCZaOIve2Zzc/iy6R3w2WjiH3tmS3P4cukd8Llo4j97Zmtz+PLpHfD5auIDe2Zbc/gK6R3whWriI3tme
3P4iukd8MVq4hN7Zkdz+ErpHfClauIze2Znc/jK6R3w5WriC3tmV3P4Kukd8JVq4it7Zndz+KrpHfDVauIbe2ZPc/hq6R3wtWriO
3tmb3P46ukd8PVq4gd7Zl9z+BrpHfCNauIk+2p/8JnroZrpHfAtauJXeOYjc/la6R3wbWrid3jmE3P52ukd8B1q4k945jNz+TrpH
fBdauJveOYLc/m66R3wPWriX3jmK3P5eukd8H1q4n945htz+frpH/ABaeJDeOY7c/kG6R/wQWniY3jmB3P5hukf8CFp4lN45idz+
UbpH/BhaeJzeOYXc/nG6R/wEWniS3jmN3P5Jukf8FFp4mt45g9z+abpH/AxaeJbeOYvc/lm6R/wcWnie3jmH3P55ukf8Alp4kd45
j9z+RbpH/BJaeJneuYDc/mW6R/wKWniV3rmI3P5Vukf8Glp4nd65hNz+dbpH/AZaeJPeuYzc/k26R/wWWnib3rmC3P5tukf8Dlp4
l965itz+XbpH/B5aeJ/euYbc/n26R/wBWviQ3rmO3P5Dukf8EVr4mN65gdz+Y7pI/AlaXfQZvSP9afjP6B7x52jhC3rnVnL7L+ge
8Zdo4St653Zy+6/oHvHXaOEbeudOcvtv6B7xt2jhO3rnbnL77+ge8fdo4Qd6515y+x/oHvGPaOEneud+cvuf6B7xz2jhF3rnQXL7
X+ge8a9o4Td652Fy+9/oHrEWbHgUP2BQr3ceJbcXPw4PRAuDBvV6R1q5vfhJeDBaGDKo1zvSyu3FT8ND0cKwQb3ekVZuL34WHo4W
/jCo1zvSyu3Fz8Mjo4U/Dur1jrRye/GL8Cho4U+Der0jrdxe/DI8KloYbVCvd6SV24tfhUdHC2MM6vWOtHJ78evwmGjhz4N6vSOt
3F78JjwWWvjLoF7vSCu3F78Nj40WxhnU6x1p5fbid+Fx0cJ4g3q9I63cXvw+PD5amGBQr3eklduLP4T/ihYmHNTrHWnl9uKP4b+h
hYkG9fpIWrm8eujvg3rdI/4HWph4UK93pJXbi7+A/4kWJhnU6x1p5fbir+BJ0cK/BvV6R1q5vfgbeDK08O9Bvd6RVm4v/g6eHC38
Z1Cvd6SV24t/gKdAC/8d1OsdaeX24p/g/6GFKQf1ekdaub34F3gqtDD1oF7vSCu3F/8GT4MWph3U6x1p5fbT0kXi6dDC9PTRAHL7
6eki8QxoYUb6aBC5/Yx0kXgmtDAzfTSE3H5mukg8C1qYlT4aRm4/K10kng0tzE4f/YHcfna6SDwHWpiTPvojuf2cdJG4Dy109NGf
yO07ukjc0ELRR6OR2xddJJ4LLcxNH41Bbj83XSSeBy3MSx/9mdx+XrpIPB9amJ8++gu5/fx0kXgBtLAgfTQOuf2CdJF4IbSwMH00
Hrn9wnSReBG0sCh9NAG5/aJ0kXgxtLA4fTQhuf3idJF4CbS6aCn6SHrJ8EvRReKl0cIy9NHE5PbL0EXiZdHCcvTRJOT2y9FF4uXR
wgr00b/I7Vegi8QrooWV6KN/k9uvRBeJV0YLq9BH/yG3X4UuEq+KFlajj/5Lbr8aXSReHS2sQR9NSW6/Bl0kXhMtrEUfTU1uvxbd
I14bLaxD70xLbr8O3SNeFy2sR+9MT26/Ht0jXh8tbEDvzEhuvwHdI94QLWxE78xMbr8R3SPeGC1sQu/MSm6/Cd0j3hQtbEbvzE5u
vxndI94cLWxB78xJbr8F3SPeEi1sRe905PZb0T3irdHCNvROkdtvQ/eIt0UL29E7c5Pbb0f3iLdHCzvQO/OS2+9A94h3RAs70Tvz
k9vvRPeId0YLu9A7C5Lb70L3iHdFC7vROwuT2+9G94h3Rwt70DuLktvvQfeI90QLe9FHi5PvRQ/tTfeI90EL+9I7S5Hb70v3iPdD
C/vTO8uQ2+9P94gPQAsH0jvLkdsfSPeID0ILB9M7K5DbH0z3iA9BC4fSOyuR2x9K94gPQwuH0zurkNsfTveIj0ALR9I7q5HbH0n3
iI9CC0fTO2uQ2x9N94iPQQvH0jtrkdsfS/eIj0MLx9M765DbH0/3iE9ACyfSO+uR259I94hPQgsn0zsbkNufTPeIT0ELp9I7G5Hb
n0r3iE9DC6fTO5uQ259O94jPQAtn0jubkdufSfeIz0ILZ9M7W5Dbn033iM9BC+fSO1uR259L94jPQwvn0zvbkNufT/eIL0ALF9I7
25HbX0j3iC9CCxfTOzuQ219M94gvQQuX0js7kdtfSveIL0MLl9M7u5DbX073iK9AC1fSO7uR219J94ivQgtX0zt7kNtfTReJr0Gr
i66jd6SvDX8d3SO+Hi3cQO/sS25/A90jvhEt3ETv7E9ufxPdI74ZLdxC7xxIbn8L3SO+FS3cRu8cTG5/G90jvh0t3EHvHEpufwfd
I74TLdxF7xxObn8X3SO+Gy3cQ+8cSW5/D90jvhct3EfvHE1ufx/dI74fLTxA7xxLbv8A3SN+EC08RO8cT27/EN0jfhgtPELvnEhu
/wjdI34ULTxG75xMbv8Y3SN+HC08Qe+cSm7/BN0jfhItPEXvnE5u/xTdI34aLTxD75xJbv8M3SN+Fi08R++cTW7/HN0jfh4tvEDv
nEtu/wLdI34RLbxE75xPbv8S3SN+GS28Qu9cSG7/Ct0jfhUtvEbvXExu/xrdI34dLbxB71xKbv8G3SN+Ey28Re9cTm7/Ft0jfhst
vEPvXElu/w7dI34XLbxHH11N/h499D7dI/4ALXxI71xHbv8h3SP+CC18TO/cQG7/Md0j/gQtfErv3ERu/yndI/4MLXxO79xCbv85
3SP+Ai18Se/cRm7/Jd0j/gotfE3v3EFu/zXdI/4GLXxL79xFbv8t3SP+Di18T+/cQ27/Pd0j/gEt/Ejv3Edu/yPdI/4JLfxM7zxA
bv8z3SP+BS38Su88RG7/K90j/g0taCHkR9G/hRc/Bg9ACwMH93pHWrm9+Al4EFoYPLjXO9LK7cVPwUPQwtDBvd6RVm4vfgYehhaG
D+71jrRye/Fz8B/QwsiDe70jrdxe/AL8R7QwyuBe70grtxe/BP8JLYw6uNc70srtxa/Ao6GF0Qf3ekdaub34NXgMtDDm4F7vSCu3
F78B/xktjDW41zvSyu3Fb8F/QQtjD+71jrRye/E78DhoYdzBvd6RVm4vfg8eD60ummBwr3ekxx/8/178IfxXtDDh4F7vSCu3F38M
/w0tTDS41zvSyu3Fn8J/Rwv/GNzrHWnl9uLP4YnRwj8H93pHWrm9+Et4ErQw6eBe70grtxd/Df8LLUw2uNc70srtxd/C/0YLkw/u
9Y60cnvx9/B/0MIUg3u9I63cXvwj/F+08L/Bvd6RVm4v/hmeEi1MNbjXO9LK7cW/wlOjhWkG93pHWrn9NCzYLp528P8v4D4dfTQS
uf10dJF4erQwA300kNx+BrpIPCNamIk+GkxuPxNdJJ4ZLcxCHw0lt5+FLhLPihZmo4+Gk9vPRheJZ0cLc9BHI5Pbz0EXiedEC330
0Sjk9n10kbhDC40+GpXcvtFF4kILc9FHo5Pbz0UXiedGC/PQR2OS289DF4nnRQvz0UdjkdvPRxeJ50cLC9BHY5PbL0AXiRdECwvR
R+OSy6uHFqaLxIughUXpownI7Reli8SLoYXF6aMJye0Xp4vES6CFJemjicjtl6SLxEuhhaXpo3+Q2y9NF4mXQQvL0kf/JLdfli4S
L4cWlqePJiW3X54uEq+AFlakjyYjt1+RLhKvhBZWpo8mJ7dfmS4Sr4IWVqWPpiC3X5UuEq+GFlanj/5Hbr86XSReAy2sSR9NRW6/
Jt0jXgstrE3vTENuvzbdI14HLaxL70xHbr8u3SNeDy2sT+/MQG6/Pt0j3gAtbEjvzERuvyHdI94ILWxM78xCbr8x3SPeBC1sSu/M
Rm6/Kd0j3gwtbE7vzEFuvzndI94CLWxJ7/SR229J94i3Qgtb0zuN3H5ruke8DVrYlt6Zi9x+W7pHvB1a2J7emYfcfnu6R7wDWtiR
3pmP3H5Huke8E1rYmd5ZgNx+Z7pIvAtaXbQbvSO9a/jd6B7x7mhhD3pnUXL7Pege8Z5oYS96Z3Fy+73oHvHeaGEfemdJcvt96B7x
vmhhP3pnaXL7/ege8f5o4QB6Z1ly+wPoHvGBaOEgemd5cvuD6B7xwWjhEHpnRXL7Q+ge8aFo4TB6Z2Vy+8PoHvHhaOEIemdVcvsj
6B7xkWjhKHpndXL7o+ge8dFo4Rh6Z01y+2PoHvGxaOE4emdtcvvj6B7x8WjhBHpnXXL7E+ge8Ylo4SR6Z31y+5PoHvHJaOEUemdD
cvtT6B7xqWjhNHpnY3L70+ge8elo4Qx6Z1Ny+zPoHvGZaOEsemdzcvuz6B7x2WjhHHpnS3L7c+ge8blo4Tx6Z2ty+/PoHvH5aOEC
emdbcvsL6B7xhWjhInpne3L7i+ge8cVo4RJ6Z0dy+0voHvGlaOEy+mhn8svoocvpHvEVaOFKemc3cvsr6R7xVWjhanpnD3L7q+ke
8TVo4Vp6Zy9y+2vpHvF1aOF6emcfcvvr6R7xDWjhRnpnP3L7G+ke8U1o4WZ65wBy+5vpHvEtaOFWeucgcvtb6R7xbWjhdnrnEHL7
2+ke8R1o4U565zBy+zvpHvFdaOFueucIcvu76R7xPWjhXnrnKHL7e+ke8X1o4X565xhy+/vpHvEDaOFBeuc4cvsH6R7xQ2jhYXrn
BHL7h+ke8SNo4VF65yRy+0fpHvFjaOFxeucUcvvH6R7xE2jhSXrnNHL7J+ke8VNo4Wl65wxy+6fpHvEzaOFZeucscvtn6R7xc2jh
eXrnHHL75+ke8Qto4UV65zxy+xfpHvFLaOFleucCcvuX6R7xK2jhVXrnInL7V+ke8Wto4XV65xJy+9fpIvEbaHXRW/SO9Jvh36J7
xG+jhXfonSvJ7d+he8TvooX36J2rye3fo3vE76OFD+ida8ntP6B7xB+ihY/onevJ7T+ie8Qfo4VP6J0bye0/oXvEn6KFz+idm8nt
P6N7xJ+jhS/onVvJ7b+ge8RfooWv6J3bye2/onvEX6OFb+idO8ntv6F7xN+ihe/onbvJ7b+je8Tfo4Uf6J17ye1/oHvEP6KFn+id
+8ntf6J7xD+jhV/onQfJ7X+he8S/ooXf6J2Hye1/o3vE2pDwUfyAIb3eeZTcXvw4PBAtDBrS6x1p5fbiJ+HBaGHIkF7vSCu3Fz8N
D0ULw4b0ekdaub34WXg4WvjDkF7vSCu3Fz8Pj4wW/jik1zvSyu3FL8KjoIU/Den1jrRye/HL8KhoYbQhvd6RVm4vfhUeHS2MMaTX
O9LK7cWvw2OihT8P6fWRtHJ59dBYQ3rdI/4LWhh7SK93pJXbi9+Bx0EL4w7p9Y60cnvxe/B4aGH8Ib3ekVZuL/4AngAt/HVIr3ek
lduLP4InRAt/G9LrHWnl9uJP4InQwt+H9HpHWrm9+DP4H2hh4iG93pFWbi/+Av4nWphkSK93pJXbi7+CJ0UL/xrS6x1p5fbib+DJ
0MK/h/R6R1q5vfg7eHK08J8hvd6RVm4v/gGeAi38d0ivd6SV24t/gv+HFqYc0usdaeX24l/gqdDC1EN6vSOt3F78GzwNWph2SK93
pJXbT0sXiadDC9PTRwPI7aeni8QzoIUZ6aNB5PYz0kXimdDCzPTREHL7meki8SxoYVb6aBi5/ax0kXg2tDA7ffQHcvvZ6SLxHGhh
Tvroj+T2c9JF4j600NFHfyK37+gicUMLRR+NRm5fdJF4LrQwN300Brn93HSReB60umg++kh63vDz0UXi+dHCAvTR2OT2C9BF4gXR
wkL00bjk9gvRReKF0cIi9NH45PaL0EXiRdHCYvTRX8ntF6OLxIujhSXoo7+R2y9BF4mXRAtL0Ud/J7dfii4SL40WlqGPJia3X4Yu
Ei+LFpajjyYht1+OLhIvjxZWoI/+RW6/Al0kXhEtrEQf/ZvcfiW6SLwyWliFPvoPuf0qdJF4VbSwGn30X3L71egi8epoYQ36aEpy
+zXoIvGaaGEt+mhqcvu16B7x2mhhHXpnWnL7dege8bpoYT16Z3py+/XoHvH6aGEDemdGcvsN6B7xhmhhI3pnZnL7jege8cZoYRN6
Z1Zy+03oHvGmaGEzemd2cvvN6B7x5mhhC3pnTnL7Lege8ZZoYSt6pyO334ruEW+NFrahd4rcfhu6R7wtWtiOPpqbfDt6aHu6R7wD
WtiR3pmP3H5Huke8E1rYmd5ZgNx+Z7pHvAta2JXeWYjcfle6R7wbWtid3lmE3H53uke8B1rYk95ZjNx+T7pHvBda2JveWYLcfm+6
R7wPWtiX3lmK3H5fuke8H1rYn95Zhtx+f7pHfABaOJDeWY7c/kC6R3wQWjiY3lmB3P5gukd8CFo4lN5Zidz+ULpHfBhaOJzeWYXc
/nC6R3wEWjiS3lmN3P5Iukd8FFo4mt5Zg9z+aLpHfAxaOJbeWYvc/li6R3wcWjie3lmH3P54ukd8Alo4kd5Zj9z+RLpHfBJaOJne
2YDc/mS6R3wKWjiV3tmI3P5Uukd8Glo4nd7ZhNz+dLpHfAZaOJPe2Yzc/ky6R3wWWjib3tmC3P5sukd8Dlo4l97Zitz+XLpHfB5a
OJ/e2Ybc/ny6SHwBWl10Eb0jfWH4i+ge8cVo4RJ6Z0dy+0voHvGlaOEyemdncvvL6B7x5WjhCnpnV3L7K+ge8ZVo4Sp6Z3dy+6vo
HvHVaOEaemdPcvtr6B7xtWjhOnpnb3L76+ge8fVo4QZ6Z19y+xvoHvGNaOEmemd/cvub6B7xzWjhFnrnQHL7W+ge8a1o4TZ652By
+9voHvHtaOEOeudQcvs76B7xnWjhLnrncHL7u+ge8d1o4R5650hy+3voHvG9aOE+eudocvv76B7x/WjhAXrnWHL7B+ge8YNo4SF6
53hy+4foHvHDaOEReudEcvtH6B7xo2jhMXrnZHL7x+ge8eNo4Ql651Ry+yfoHvGTaOEpeud0cvun6B7x02jhGXrnTHL7Z+ge8bNo
4Tl652xy++foHvHzaOEFeudccvsX6B7xi2jhJfrofPKX6KGX6R7xK2jhVXrnInL7V+ke8Wto4XV65xJy+9fpHvEbaOFNeucycvs3
6R7xW2jhbXrnCnL7t+ke8Tto4V165ypy+3fpHvF7aOF9eucacvv36R7xB2jhQ3rnOnL7D+ke8Udo4WN65wZy+4/pHvEnaOFTeucm
cvtP6R7xZ2jhc3rnFnL7z+ke8Rdo4Ut65zZy+y/pHvFXaOFreucOcvuv6R7xN2jhW3rnLnL7b+ke8Xdo4Xt65x5y++/pHvEPaOFH
euc+cvsf6R7xT2jhZ3rnAXL7n+ke8S9o4Vd65yFy+1/pHvFvaGGkob3eeYTcXvwYPAAtDBza6x1p5fbiJ+BBaGHw0F7vSCu3Fz8F
D0ELQ4f2ekdaub34GXgYWhg+tNc70srtxc/Bf0ALIw/t9Y60cnvxC/Af0cIoQ3u9I63cXvwS/Ce0umi0ob3ekR516P978avw6Ghh
jKG93pFWbi9+HR4TLfx5aK93pJXbi9+Ex0ILfxna6x1p5fbit+Gx0cI4Q3u9I63cXvwuPC5aGG9or3eklduL34fHRwsTDO31jrRy
e/GH8F/RwoRDe70jrdxe/DH8N7Qw0dBe70grtxd/Cv8dLfxjaK93pJXbiz+HJ0YL/xza6x1p5fbiL+FJ0MKkQ3u9I63cXvw1/C+0
MNnQXu9IK7cXfwv/Gy1MPrTXO9LK7cXfw/9BC1MM7fWOtHJ78Y/wf9HC/4b2ekdaub34Z3hKtDDV0F7vSCu3F/8KT40Wphna6x1p
5fbikfDTooXp6KORyO2no4vE06OFGeijgeT2M9BF4hnRwkz00WBy+5noIvHMaGEW+mgouf0sdJF4VrQwG300nNx+NrpIPDtamIM+
Gpncfg66SDwnWuijj0Yhl1cPdXSRuKGFoo9GI7cvukg8F1qYmz4ag9x+brpIPA9amJc++jO5/bx0kXg+tDA/ffQXcvv56SLxAmhh
QfpoHHL7Beki8UJoYWH6aDxy+4XpIvEiaGFR+mgCcvtF6SLxYmhhcfpoQnL7xeki8RJoYUn6aCJy+yXpIvFSaGFp+ugf5PZL00Xi
ZdDCsvTRP8ntl6WLxMuhheXpo0nJ7Zeni8QroIUV6aPJyO1XpIvEK6GFlemjycntV6aLxKughVXpoynI7Veli8SroYXV6aP/kduv
TheJ10ALa9JHU5Hbr0n3iNdCC2vTO9OQ269N94jXQQvr0jvTkduvS/eI10ML69M7M5Dbr0/3iDdACxvSOzOR229I94g3Qgsb0zuz
kNtvTPeIN0ELm9I7s5Hbb0r3iDdDC5vTO3OQ229OF4m3QKuLtqJ3pLcMvxXdI94aLWxD7xS5/TZ0j3hbtLAdvTM3uf12dI94e7Sw
A70zL7n9DnSPeEe0sBO9Mz+5/U50j3hntLALvbMguf0udI94V7SwG72zMLn9bnSPeHe0sAe9syi5/R50j3hPtLAXvbM4uf1edI94
b7SwD72zJLn9PnSPeF+0sB+9szS5/X50j3h/tHAAvbMsuf0BdI/4QLRwEL2zPLn9QXSP+GC0cAi9syK5/SF0j/hQtHAYvbMyuf1h
dI/4cLRwBL2zKrn9EXSP+Ei0cBS9szq5/VF0j/hotHAMvbMmuf0xdI/4WLRwHL2zNrn9cXSP+Hi0cAK9sy65/Ql0j/hEtHASvbM+
uf1JdI/4ZLRwCr2zIbn9KXSP+FS0cBq9szG5/Wl0j/h0tHAGvbMpuf0ZdI/4TLRwFn20OflZ9NDZdI/4HLRwLr2zFbn9uXSP+Dy0
cD69sw25/fl0j/gCtHAhvbMduf2FdI/4IrRwMb2zA7n9xXSP+BK0cCm9sxO5/aV0j/gytHA5vbMLuf3ldI/4CrRwJb2zG7n9lXSP
+Cq0cDW9swe5/dV0j/gatHAtvbMXuf21dI/4OrRwPb2zD7n99XSP+Aa0cCO9sx+5/Y10j/gmtHAzvXMAuf3NdI/4FrRwK71zELn9
rXSP+Da0cDu9cwi5/e10j/gOtHAnvXMYuf2ddI/4LrRwN71zBLn93XSP+B60cC+9cxS5/b10j/g+tHA/vXMMuf39dI/4AbTwIL1z
HLn9g3SP+CG08DC9cwK5/cN0j/gRtPAovXMSuf2jdI/4MbTwOL1zCrn943SP+Am08CS9cxq5/ZN0j/gptPA0vXMGuf3TdJH4GbS6
6Dl6R/rZ8M/RPeLn0cIL9M655PYv0D3iF9HCS/TO+eT2L9E94pfRwiv0zoXk9q/QPeJX0cJr9M7F5Pav0T3i19HCG/TOpeT2b9A9
4jfRwlv0zuXk9m/RPeK30cI79M6V5Pbv0D3id9HCe/TO1eT279E94vfRwgf0zrXk9h/QPeIP0cJH9M715PYf0T3ij9HCJ/TOjeT2
n9A94k/Rwmf0zs3k9p/RPeLP0cIX9M6t5PZf0D3iL9HCV/TO7eT2X9E94q/Rwjf0zp3k9t/QPeJv0cJ39M7d5Pbf0T3i79HCD/TO
veT2P9A94h/Rwk/0zv3k9j/RPeKf0cIv9M6D5Pa/0D3iX9HCb/TOw+T2v9E94pGG9bQwYFivdx4ltxc/Dg9EC4OG9XpHWrm9+El4
MFoYMqzXO9LK7cVPw0PRwrBhvT6SVi6vHho+rNc94j+ghZGH9XpHWrm9+AX4j2hhlGG93pFWbi9+Cf4TWhh1WK93pJXbi1+BR0ML
ow/r9Y60cnvxa/AYaGHMYb3ekVZuL34D/jNaGGtYr3eklduL34L/ghbGHtbrHWnl9uJ34HHQwrjDer0jrdxe/B48HloYf1ivd6SV
24s/gCdAC38d1usdaeX24o/gCdHC34b1ekdaub34E3gitPD3Yb3ekVZuL/4M/gdamHhYr3eklduLv4D/iRYmGdbrHWnl9uKv4EnR
wr+G9XpHWrm9+Bt4MrTw72G93pFWbi/+Dp4cLfxnWK93pJXbi3+Ap0AL/x3W6x1p5fbin+D/oYUph/V6R1q5vfgXeCq0MPWwXu9I
K7cX/wZPgxamHdbrHWnl9tPSReLp0ML09NEAcvvp6SLxDGhhRvpoELn9jHSReCa0MDN9NITcfma6SDwLWl00G30kPWv42egi8exo
YQ76aGRy+znoIvGcaKGPPhqF3L6PLhJ3aKHRR6OS2ze6SFxoYS76aHRy+7noIvHcaGEe+mhMcvt56CLxvGhhPvpoLHL7+egi8fxo
YQH6aGxy+wXoIvGCaGEh+mhccvuF6CLxwmhhEfpofHL7Regi8aJoYTH66K/k9ovRReLF0cIS9NHfyO2XoIvES6KFpeijv5PbL0UX
iZdGC8vQRxOT2y9DF4mXRQvL0UeTkNsvRxeJl0cLK9BH/yK3X4EuEq+IFlaij/5Nbr8SXSReGS2sQh/9h9x+FbpIvCpaWI0++i+5
/Wp0kXh1tLAGfTQluf0adJF4TbSwFn00Nbn9WnSPeG20sA69My25/Tp0j3hdtLAevTM9uf16dI94fbSwAb0zI7n9BnSPeEO0sBF9
NDP5RvTQxnSPeBO0sCm9Mxu5/aZ0j3gztLA5vTMHuf3mdI94C7SwJb3TR26/Jd0j3gotbE3vNHL7reke8TZoYVt6Zy5y+23pHvF2
aGF7emcecvvt6R7xDmhhR3pnPnL7Heke8U5oYWd6ZwFy+53pHvEuaGFXemchcvtd6R7xbmhhd3pnEXL73eke8R5oYU96ZzFy+z3p
HvFeaGFvemcJcvu96R7xPmhhX3pnKXL7feke8X5oYX96Zxly+/3pHvEBaOFAemc5cvsD6R7xQWjhYHpnBXL7g+ke8SFo4VB6ZyVy
+0PpHvFhaOFwemcVcvvD6R7xEWjhSHpnNXL7I+ke8VFo4Wh6Zw1y+6PpHvExaOFYemctcvtj6R7xcWjheHpnHXL74+ke8Qlo4UR6
Zz1y+xPpHvFJaOFkemcDcvuT6SLxKWh10Wn0jvSp4U+je8Sno4Uz6J1Nye3PoHvEZ6KFs+idzcntz6J7xGejhXPonS3J7c+he8Tn
ooXz6J2tye3Po3vE56OFC+idbcntL6B7xBeihYvone3J7S+ie8QXo4VL6J0dye0voXvEl6KFy+idncntL6N7xJejhSvonV3J7a+g
e8RXooWr6J3dye2vonvEV6OFa+idPcntr6F7xNeihevonb3J7a+je8TXo4Ub6J19ye1voHvEN6KFm+id/cntb6J7xDejhVvonQPJ
7W+he8S3ooXb6J2Dye1vo3vEt6OFO+idQ8nt76B7xHeihbvoncPJ7e+ie8R3o4V76J0jye3voXvE96KF++ido8nt76N7xPejhQfo
nWPJ7R+ge8QPooWH6J3jye0fonvED6OFR+idE8ntH6F7xI+ihcfoo5PJH6OHHqd7xE+ghSfpndPI7Z+ke8RPoYWn6Z0zyO2fpnvE
z6CFZ+mds8jtn6V7xM+hhefpnXPI7Z+ne8QvoIUX6Z3zyO1fpHvEL6GFl+mdC8jtX6Z7xK+ghVfpnYvI7V+le8SvoYXX6Z1LyO1f
p3vEb6CFN+mdy8jt36R7xG+hhbfpnSvI7d+me8TvoIV36Z2ryO3fpXvE76GF9+mda8jt36d7xB+ghQ/pnevI7T+ke8QfoYWP6Z0b
yO0/pnvEn6CFT+mdm8jtP6V7xJ+hhc/pnVvI7T+ne8RfoIUv6Z3byO2/pHvEX6GFr+mdO8jtv6Z7xN+ghW/pnbvI7b+le8TfoYXv
6Z17yO2/p3vEP6CFH+md+8jtf6R7xD+hhZ/pnQfI7X+me8S/oIVf6Z2HyO1/pXvEv6GFkYb3eucRcnvxY/AAtLpo0PBe70gPHP7/
XvwkPBgtDBne6x1p5fbip+GhaGHY8F7vSCu3Fz8LD0cLfxje6x1p5fbi5+GR0cIfh/d6R1q5vfhFeBS08Kfhvd6RVm4vfhkeFS2M
NrzXO9LK7cWvwqOjhTGG93pHWrm9+HV4TLTw5+G93pFWbi9+Ex4LLfxleK93pJXbi9+Gx0YL4wzv9Y60cnvxu/C4aGG84b3ekVZu
L34fHh8tTDC81zvSyu3FH8J/RQsTDu/1jrRye/HH8N/QwkTDe70jrdxe/Cn8d7Twj+G93pFWbi/+HJ4YLfxzeK93pJXbi7+EJ0EL
kw7v9Y60cnvx1/C/0MJkw3u9I63cXvwt/G+0MPnwXu9IK7cXfw//By1MMbzXO9LK7cU/wv9FC/8b3usdaeX24p/hKdHCVMN7vSOt
3F78Kzw1WphmeK93pJXbi0fCT4sWpqOPRiL/vybKslvIhIyiOP1Od3eniAzd3d05zJ07dHd3N3PnDkN3d3cOIoqIiIiIiIiIiIiI
iIgyrr3e/Sz5cNbZ5/yAzcZDH+siOo9M8uqjO/1j59VFdD6Z5NdHd/vHzq+L6AIyKaiP7vWPXVAX0YVkUlgfJf6xC+siuohMiuqj
B/xjF9VFdDGZFNdHD/nHLq6L6BIyKamPHvGPXVIX0aVkUlofPeYfu7QuosvIpKw+esI/dlldRJeTSXl99JR/7PK6iK4gk4r66Bn/
2BV1EV1JJpX10XP+sSvrIrqKTKrqoxf8Y1fVRXQ1mVTXRy/5x66ui+gaMqmpj17xj11TF9G1ZFJbH73mH7u2LqLryKSuPnrDP3Zd
XUTXk0l9ffSWf+z6uohuIJOG+ugd/9gNdRHdSCaN9dF7/rEb6yK6iUya6qMP/GM31UX0JzJppo8+8o/dTBfRn8okQx/l9I+doXvo
z2SSqXdy+cfO1EX05zIuaqF34Oa37Ra6h24pk1Z6J69/7Fa6h24tkzZ6J79/7Da6h24rk3Z6p6B/7Ha6h24vkw56p7B/7A66h+4o
k056p6h/7E66h+4sky56p7h/7C66h+4qk256p6R/7G66h+4ukx56p7R/7B66h+4pk156p6x/7F66h+4tkz56p7x/7D66h+4rk356
p6J/7H66h+4vkwF6p7J/7AG6hx4ok0F6p6p/7EG6hx4skyF6p7p/7CG6hx4qk2F6p6Z/7GG6hx4ukxF6p7Z/7BG6hx4pk1F6p65/
7FG6hx4tkzF6p75/7DG6hx4rk3F6p6F/7HG6hx4vkwl6p7F/7Am6h54ok0l6p6l/7Em6h/5CJll6p5l/7CzdQ38pk2y9k+EfO1v3
0F/JZLI+yvSfrIe+1j30FJlM1Tst/GNP1T30NJlM1zut/GNP1z30DJnM1Dtt/GPP1D30LJnM1jvt/GPP1j30HJnM1Tsd/GPP1T30
PJnM1zud/GPP1z30Apks1Dtd/GMv1D30Ipks1jvd/GMv1j30Epks1Ts9/GMv1T30Mpks1zu9/GMv1z30Cpms1Dt9/GOv1D30Kpms
1jv9/GOv1j30Gpms1TsD/GOv1T30Opms1zuD/GOv1z30Bpls1DtD/GNv1D30Jpls1jvD/GNv1j30Fpls1Tsj/GNv1T30Npls1zuj
/GNv1z30Dpns1Dtj/GPv1D30Lpns1jvj/GPv1j30Hpns1TsT/GPv1T30NzLZp3cm+cfep3voH8hkv97J8o+9X/fQP5TJAb2T7R/7
gC6ifyTjooN6B/7xbfug7qF/IpNDemeqf+xDuof+qUwO653p/rEP6x76ZzI5ondm+sc+onvon8vkqN6Z7R/7qO6hfyGTY3pnrn/s
Y7qH/qVMjuud+f6xj+se+lcyOaF3FvrHPqF76F/L5KTeWewf+6TuoX8jk1N6Z6l/7FO6h/6tTE7rneX+sU/rHvp3Mjmjd1b6xz6j
e+jfy+Ss3lntH/us7qH/IJNzemetf+xzuof+o0zO6531/rHP6x76TzK5oHc2+se+oHvoP8vkot7Z7B/7ou6h/yKTS3pnq3/sS7qH
/qtMLuud7f6xL+se+m8yuaJ3dvrHvqJ76L/L5Kre2e0f+6ruof8hk2t6Z69/7Gu6h/6nTK7rnX3+sa/rHvpfMrmhd/b7x76he+h/
y+SmPjrgf1MP/Uf30P+VyS29c9A/9i3dQ38rkxxJ6p1D/rHpw/Z3ZHJHknoH5o9NH7HvlMldSeodmD82fdS+Wyb3JKl3YP7Y9DH7
Xpncl6Tegflj08ftRCb3J6l3YP7Y9An7AZk8mKTegflj0yfth2TycJJ6B+aPTZ+yH5HJo0nqHZg/Nn3afkwmjyepd2D+2PQZ+wmZ
PJmk3oH5Y9Nn7adk8nSSegfmj02fs5+RybNJ6h2YPzZ93n5OJs8nqXdg/tj0BfsFmbyYpN6B+WPTF+2XZPJyknoH5o9NX7Jfkcmr
SeodmD82fdl+TSavJ6l3YP7Y9BX7DZm8maTegflj01ftt2TydpJ6B+aPTV+z35HJu0nqHZg/Nn3dfk8m7yepd2D+2PQN+wOZfJik
3oH5Y9M37Y9kXJQzSb0Dfzf5/6Zv2d+TSa4k9Q7MH5vO4f6+THLroxz+sXPrIvpjmeTRR3f4x86ji+i8Msmnj+7yj51PF9H5ZVJA
H93jH7uALqILyqSQPrrPP3YhXUQXlkkRfXS/f+wiuoguKpNi+uhB/9jFdBFdXCYl9NHD/rFL6CK6pExK6aNH/WOX0kV0aZmU0UeP
+8cuo4vosjIpp4+e9I9dThfR5WVSQR897R+7gi6iK8qkkj561j92JV1EV5ZJFX30vH/sKrqIriqTavroRf/Y1XQRXV0mNfTRy/6x
a+giuqZMaumjV/1j19JFdG2Z1NFHr/vHrqOL6LoyqaeP3vSPXU8X0fVl0kAfve0fu4EuohvKpJE+etc/diNdRDeWSRN99L5/7Ca6
iG4qk0/00Yf+bDzUTBfRn8okQx/l9I+doXvoz2SSqXdy+cfO1D305zJprndy+8durnvoFjJpqXfy+MduqXvoVjJprXfy+cdurXvo
NjJpq3cK+Mduq3vodjJpr3cK+cdur3voDjLpqHeK+MfuqHvoTjLprHeK+cfurHvoLjLpqndK+MfuqnvobjLprndK+cfurnvoHjLp
qXfK+MfuqXvoXjLprXfK+cfurXvoPjLpq3cq+Mfuq3vofjLpr3cq+cfur3voATIZqHeq+MceqHvoQTIZrHeq+ccerHvoITIZqndq
+MceqnvoYTIZrndq+ccernvoETIZqXfq+MceqXvoUTIZrXfq+ccerXvoMTIZq3ca+Mceq3vocTIZr3ca+ccer3voCTKZqHea+Mee
qIvoSTIuytI78Be37SzdQ38pk2y9k+EfO1v30F/JZLLeyfSPPVn30F/LZIreae4fe4ruoafKZJreaekfe5ruoafLZIbeae0fe4bu
oWfKZJbeaesfe5buoWfLZI7eae8fe47uoefKZJ7e6egfe57uoefLZIHe6ewfe4HuoRfKZJHe6eofe5HuoRfLZIne6e4fe4nuoZfK
ZJne6ekfe5nuoZfLZIXe6e0fe4XuoVfKZJXe6esfe5XuoVfLZI3e6e8fe43uodfKZJ3eGegfe53uodfLZIPeGewfe4PuoTfKZJPe
Geofe5PuoTfLZIveGe4fe4vuobfKZJveGekfe5vuobfLZIfeGe0fe4fuoXfKZJfeGesfe5fuoXfLZI/eGe8fe4/uoffK5Bt9NNGf
/T/2pCCl
"""


def load_mesh(source):
    if source == "usd":  # the example's way (needs pxr and warp's example assets)
        import warp.examples
        from pxr import Usd

        import newton.usd

        stage = Usd.Stage.Open(os.path.join(warp.examples.get_asset_directory(), "square_cloth.usd"))
        m = newton.usd.get_mesh(stage.GetPrimAtPath("/root/cloth/cloth"))
        return np.asarray(m.vertices), np.asarray(m.indices)
    raw = zlib.decompress(base64.b64decode("".join(MESH_B64.split())))
    assert hashlib.sha256(raw).hexdigest() == MESH_SHA256, "embedded mesh corrupted"
    v = np.frombuffer(raw[: MESH_NV * 12], dtype="<f4").reshape(MESH_NV, 3).copy()
    i = np.frombuffer(raw[MESH_NV * 12 :], dtype="<i4").copy()
    assert i.size == MESH_NI
    return v, i


class Twist:
    """Example.__init__ / simulate() of example_cloth_twist.py, less the viewer (whose apply_forces is a
    no-op for the null viewer the example's --benchmark/--viewer null runs use)."""

    def __init__(self, mesh, selfcontact=True, device=None):
        self.fps = 60
        self.frame_dt = 1.0 / self.fps
        self.sim_time = 0.0
        self.sim_substeps = 10  # must be an even number when using CUDA Graph
        self.sim_dt = self.frame_dt / self.sim_substeps
        self.iterations = 4
        self.rot_angular_velocity = math.pi / 3
        self.rot_end_time = 10
        self.selfcontact = selfcontact

        mesh_points, mesh_indices = mesh
        vertices = [wp.vec3(v) for v in mesh_points]
        self.faces = mesh_indices.reshape(-1, 3)

        with wp.ScopedDevice(device):
            scene = newton.ModelBuilder(gravity=(0.0, 0.0, 0.0))
            scene.add_cloth_mesh(
                pos=wp.vec3(0.0, 0.0, 0.0),
                rot=wp.quat_from_axis_angle(wp.vec3(0, 0, 1), np.pi / 2),
                scale=0.01,
                vertices=vertices,
                indices=mesh_indices,
                vel=wp.vec3(0.0, 0.0, 0.0),
                density=0.2,
                tri_ke=1.0e3,
                tri_ka=1.0e3,
                tri_kd=2.0e-4,
                edge_ke=1e-3,
                edge_kd=1e-2,
            )
            scene.color()
            self.model = scene.finalize()
            self.model.soft_contact_ke = 1.0e3
            self.model.soft_contact_kd = 1.0e-1
            self.model.soft_contact_mu = 0.2

            cloth_size = 50
            left_side = [cloth_size - 1 + i * cloth_size for i in range(cloth_size)]
            right_side = [i * cloth_size for i in range(cloth_size)]
            rot_point_indices = left_side + right_side

            if len(rot_point_indices):
                flags = self.model.particle_flags.numpy()
                for fixed_vertex_id in rot_point_indices:
                    flags[fixed_vertex_id] = flags[fixed_vertex_id] & ~ParticleFlags.ACTIVE
                self.model.particle_flags = wp.array(flags)

            self.solver = newton.solvers.SolverVBD(
                self.model,
                iterations=self.iterations,
                particle_enable_self_contact=selfcontact,  # the example: True
                particle_self_contact_margin=0.002,
                particle_self_contact_gap=0.0015,
                particle_vertex_contact_buffer_size=64,
                particle_edge_contact_buffer_size=128,
            )
            self.state_0 = self.model.state()
            self.state_1 = self.model.state()
            self.control = self.model.control()

            self.collision_pipeline = newton.CollisionPipeline(self.model)
            self.contacts = self.collision_pipeline.contacts()

            # NB: the example pairs these axes with [right_side + left_side] while its index list is
            # [left_side + right_side]; kept as is (left_side turns about +y, right_side about -y).
            rot_axes = [[0, 1, 0]] * len(right_side) + [[0, -1, 0]] * len(left_side)

            self.rot_point_indices = wp.array(rot_point_indices, dtype=int)
            self.t = wp.zeros((1,), dtype=float)
            self.rot_centers = wp.zeros(len(rot_point_indices), dtype=wp.vec3)
            self.rot_axes = wp.array(rot_axes, dtype=wp.vec3)
            self.roots = wp.zeros_like(self.rot_centers)
            self.roots_to_ps = wp.zeros_like(self.rot_centers)

            wp.launch(
                kernel=initialize_rotation,
                dim=self.rot_point_indices.shape[0],
                inputs=[self.rot_point_indices, self.state_0.particle_q, self.rot_centers, self.rot_axes, self.t],
                outputs=[self.roots, self.roots_to_ps],
            )
        self.graph = None

    def capture(self):
        with wp.ScopedCapture() as capture:
            self.simulate()
        self.graph = capture.graph

    def simulate(self):
        self.collision_pipeline.collide(self.state_0, self.contacts)
        self.solver.rebuild_bvh(self.state_0)
        for _ in range(self.sim_substeps):
            self.state_0.clear_forces()
            # (viewer.apply_forces(self.state_0): no-op without an interactive viewer)
            wp.launch(
                kernel=apply_rotation,
                dim=self.rot_point_indices.shape[0],
                inputs=[
                    self.rot_point_indices,
                    self.rot_axes,
                    self.roots,
                    self.roots_to_ps,
                    self.t,
                    self.rot_angular_velocity,
                    self.sim_dt,
                    self.rot_end_time,
                ],
                outputs=[self.state_0.particle_q, self.state_1.particle_q],
            )
            self.solver.step(self.state_0, self.state_1, self.control, self.contacts, self.sim_dt)
            self.state_0, self.state_1 = self.state_1, self.state_0

    def step(self):
        if self.graph:
            wp.capture_launch(self.graph)
        else:
            self.simulate()
        self.sim_time += self.frame_dt

    def sanity(self):
        """The example's test_final() criteria, plus a few figures."""
        q = self.state_0.particle_q.numpy()
        qd = self.state_0.particle_qd.numpy()
        lo, hi = np.array([-0.6, -0.9, -0.6]), np.array([0.6, 0.9, 0.6])
        finite = bool(np.isfinite(q).all() and np.isfinite(qd).all())
        return {
            "finite": finite,
            "test_final_ok": bool(finite and ((q >= lo) & (q <= hi)).all() and np.abs(qd).max() < 1.5),
            "bbox_min": [round(float(x), 4) for x in q.min(0)],
            "bbox_max": [round(float(x), 4) for x in q.max(0)],
            "max_abs_qd": round(float(np.abs(qd).max()), 4),
            "t_device": round(float(self.t.numpy()[0]), 4),
        }


def run_case(a, mesh, selfcontact):
    dev = wp.get_device(a.device)
    use_graph = dev.is_cuda and not a.nograph
    # 1) warm-up instance: compiles/loads every module, runs a few frames, then is dropped
    t0 = time.perf_counter()
    w = Twist(mesh, selfcontact, dev)
    with wp.ScopedDevice(dev):
        if use_graph:
            w.capture()
        for _ in range(a.warmup):
            w.step()
        wp.synchronize_device(dev)
    warm_s = time.perf_counter() - t0
    del w
    # 2) fresh instance, timed from t = 0 (the example's frames 0 .. frames-1)
    sim = Twist(mesh, selfcontact, dev)
    with wp.ScopedDevice(dev):
        t0 = time.perf_counter()
        if use_graph:
            sim.capture()
        wp.synchronize_device(dev)
        capture_s = time.perf_counter() - t0
        per = []
        if dev.is_cuda:
            ev = [wp.Event(dev, enable_timing=True) for _ in range(a.frames + 1)]
            wp.record_event(ev[0])
            for k in range(a.frames):
                sim.step()
                wp.record_event(ev[k + 1])
            wp.synchronize_device(dev)
            per = [wp.get_event_elapsed_time(ev[k], ev[k + 1]) for k in range(a.frames)]
            total = wp.get_event_elapsed_time(ev[0], ev[-1])
            clock = "cuda_events"
        else:
            tt = time.perf_counter()
            for k in range(a.frames):
                s = time.perf_counter()
                sim.step()
                wp.synchronize_device(dev)
                per.append((time.perf_counter() - s) * 1e3)
            total = (time.perf_counter() - tt) * 1e3
            clock = "host_perf_counter"
    blocks = [per[k : k + a.block] for k in range(0, len(per), a.block)]
    bmeans = [statistics.fmean(b) for b in blocks]
    out = {
        "case": "newton_cloth_twist",
        "device": dev.name,
        "alias": dev.alias,
        "graph": use_graph,
        "clock": clock,
        "selfcontact": bool(selfcontact),
        "particles": int(sim.model.particle_count),
        "triangles": int(sim.model.tri_count),
        "edges": int(sim.model.edge_count),
        "substeps": sim.sim_substeps,
        "iterations": sim.iterations,
        "frame_dt": sim.frame_dt,
        "frames": a.frames,
        "ms_per_frame": round(total / a.frames, 4),
        "block_frames": a.block,
        "block_ms_per_frame": [round(x, 4) for x in bmeans],
        "block_min": round(min(bmeans), 4),
        "block_max": round(max(bmeans), 4),
        "frame_min": round(min(per), 4),
        "frame_median": round(statistics.median(per), 4),
        "frame_max": round(max(per), 4),
        "warmup_frames": a.warmup,
        "warmup_s": round(warm_s, 2),
        "capture_s": round(capture_s, 3),
    }
    out.update(sim.sanity())
    print("RESULT " + json.dumps(out), flush=True)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--device", default=None, help="warp device (default: warp's default, cuda:0 when present)")
    ap.add_argument("--frames", type=int, default=300, help="timed frames (the example's 300 = 5 s at 60 fps)")
    ap.add_argument("--warmup", type=int, default=10, help="frames on the throw-away compile instance")
    ap.add_argument("--block", type=int, default=100, help="frames per block for the block means")
    ap.add_argument("--selfcontact", choices=["1", "0", "both"], default="both", help="both: on, then off")
    ap.add_argument("--repeats", type=int, default=1, help="run each case this many times")
    ap.add_argument("--nograph", action="store_true", help="launch kernels one by one (no CUDA graph)")
    ap.add_argument("--mesh", choices=["embedded", "usd"], default="embedded")
    ap.add_argument("--quiet", action="store_true", help="silence warp's module-load messages")
    a = ap.parse_args()
    if a.quiet:  # as newton.examples does for --quiet
        wp.config.quiet = True
        if hasattr(wp, "LOG_WARNING"):
            wp.config.log_level = max(wp.config.log_level, wp.LOG_WARNING)
    wp.init()
    mesh = load_mesh(a.mesh)
    cases = {"1": [True], "0": [False], "both": [True, False]}[a.selfcontact]
    for sc in cases:
        for _ in range(a.repeats):
            run_case(a, mesh, sc)


if __name__ == "__main__":
    main()
