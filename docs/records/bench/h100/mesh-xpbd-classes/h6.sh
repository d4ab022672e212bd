set -u
# Issue 71: XPBD by spring classes on a mesh cloth (new) against the grid of its vertex count,
# and XPBD by Jacobi beside it; w = the tree with mesh XPBD, z = 35e4842's; interleaved.
nvidia-smi --query-gpu=name --format=csv,noheader
for f in .gl/c4/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /tmp/nw; for b in w z; do xz -dc .gl/c4/msdsim_$b.xz > /tmp/nw/msdsim_$b; chmod +x /tmp/nw/msdsim_$b; done
cd .gl/c4 && python3 make-meshes.py
run() { b=$1; shift; echo "== $b $*" | cut -c1-140; timeout 100 /tmp/nw/msdsim_$b simulate "$@" --quiet 2>&1 | grep -E "GPU frame time|error" | cut -c1-200; }
for rep in 1 2; do
  for p in grid tris quads; do run w --preset $p.toml --frames 60 --set sim.max_strain=0 --set 'sim.integrator="xpbd"'; done
  run z --preset grid.toml --frames 60 --set sim.max_strain=0 --set 'sim.integrator="xpbd"'
  for b in w z; do run $b --preset tris.toml --frames 60 --set sim.max_strain=0 --set 'sim.integrator="xpbd_jacobi"'; done
  run w --preset grid.toml --frames 60 --set sim.max_strain=0 --set 'sim.integrator="vbd"'
done
