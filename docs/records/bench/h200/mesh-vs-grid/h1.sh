set -u
# Issue 71 on the H200: a mesh cloth against a grid of its vertex count, h = 6ad6ca6's tree,
# x = 229dfe6's (drag by area, XPBD by Jacobi and the implicit method on meshes), VBD interleaved, then XPBD by Jacobi and the implicit method
# on x; the holed flag and the skirt. Copies Newton's first wheel part for h3.sh.
nvidia-smi --query-gpu=name --format=csv,noheader
for f in .gl/c4/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /tmp/nw; for b in h x; do xz -dc .gl/c4/msdsim_$b.xz > /tmp/nw/msdsim_$b; chmod +x /tmp/nw/msdsim_$b; done
cp .gl/nw0/part00 /tmp/nw/ 2>/dev/null
cd .gl/c4 && python3 make-meshes.py
run() { b=$1; shift; echo "== $b $*" | cut -c1-140; timeout 100 /tmp/nw/msdsim_$b simulate "$@" --quiet 2>&1 | grep -E "GPU frame time|error" | cut -c1-200; }
for rep in 1 2 3; do for b in h x; do for p in grid quads tris; do run $b --preset $p.toml --frames 60 --set sim.max_strain=0; done; done; done
for rep in 1 2; do for m in xpbd_jacobi implicit; do for p in grid tris; do run x --preset $p.toml --frames 60 --set sim.max_strain=0 --set "sim.integrator=\"$m\""; done; done; done
for rep in 1 2; do for b in h x; do run $b --preset ../../presets/holed_flag.toml --frames 200; run $b --preset ../../presets/skirt.toml --frames 400; done; done
