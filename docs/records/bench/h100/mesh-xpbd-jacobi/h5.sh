set -u
# Issue 71: XPBD by Jacobi on a mesh cloth against a grid of its vertex count; y = 8fc3e52's
# tree (the bound summed in its own pass every iteration), z = the bound summed once a
# substep (first iteration) and kept in the iterate's w; interleaved, then the grid.
nvidia-smi --query-gpu=name --format=csv,noheader
for f in .gl/c4/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /tmp/nw; for b in y z; do xz -dc .gl/c4/msdsim_$b.xz > /tmp/nw/msdsim_$b; chmod +x /tmp/nw/msdsim_$b; done
cd .gl/c4 && python3 make-meshes.py
run() { b=$1; shift; echo "== $b $*" | cut -c1-140; timeout 100 /tmp/nw/msdsim_$b simulate "$@" --quiet 2>&1 | grep -E "GPU frame time|error" | cut -c1-200; }
for rep in 1 2 3; do for b in y z; do run $b --preset tris.toml --frames 60 --set sim.max_strain=0 --set 'sim.integrator="xpbd_jacobi"'; done; done
for b in y z; do run $b --preset grid.toml --frames 60 --set sim.max_strain=0 --set 'sim.integrator="xpbd_jacobi"'; done
for b in y z; do run $b --preset quads.toml --frames 60 --set sim.max_strain=0 --set 'sim.integrator="xpbd_jacobi"'; done
