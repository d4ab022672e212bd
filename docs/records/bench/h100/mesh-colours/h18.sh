set -u
# Issue 71: a mesh cloth against a grid of its vertex count, before (e = 92b682d's tree: the
# triangles in 6 colours, the holed flag in 7), c = c18629e (5 and 5), d = b9f7ba5 (c and mass
# lumped by area), interleaved. Also copies Newton's first part.
nvidia-smi --query-gpu=name --format=csv,noheader
for f in .gl/c3/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /tmp/nw; for f in msdsim_e msdsim_c msdsim_d; do xz -dc .gl/c3/$f.xz > /tmp/nw/$f; chmod +x /tmp/nw/$f; done
cp .gl/nw0/part00 /tmp/nw/ 2>/dev/null
cd .gl/c3 && python3 make-meshes.py
run() { b=$1; shift; echo "== $b $*" | cut -c1-140; timeout 100 /tmp/nw/msdsim_$b simulate "$@" --quiet 2>&1 | grep -E "GPU frame time|error" | cut -c1-200; }
for rep in 1 2 3; do for b in e c d; do for p in grid quads tris; do run $b --preset $p.toml --frames 60 --set sim.max_strain=0; done; done; done
for rep in 1 2; do for b in e c d; do run $b --preset ../../presets/holed_flag.toml --frames 200; done; done
for rep in 1 2; do for b in e c d; do run $b --preset ../../presets/skirt.toml --frames 200; done; done
