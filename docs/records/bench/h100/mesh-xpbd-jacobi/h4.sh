set -u
# Issue 71 (run on an H100 here; written for the H200): XPBD by Jacobi and the implicit method on a mesh cloth against a grid of
# its vertex count; x = 229dfe6's tree, y = 8fc3e52's (83cdb39's XPBD by Jacobi's two passes and
# hessian_product over a mesh read in batches), interleaved.
nvidia-smi --query-gpu=name --format=csv,noheader
for f in .gl/c4/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /tmp/nw; for b in x y; do xz -dc .gl/c4/msdsim_$b.xz > /tmp/nw/msdsim_$b; chmod +x /tmp/nw/msdsim_$b; done
cd .gl/c4 && python3 make-meshes.py
run() { b=$1; shift; echo "== $b $*" | cut -c1-140; timeout 100 /tmp/nw/msdsim_$b simulate "$@" --quiet 2>&1 | grep -E "GPU frame time|error" | cut -c1-200; }
for rep in 1 2; do for m in xpbd_jacobi implicit; do for b in x y; do run $b --preset tris.toml --frames 60 --set sim.max_strain=0 --set "sim.integrator=\"$m\""; done; done; done
for m in xpbd_jacobi implicit; do run y --preset grid.toml --frames 60 --set sim.max_strain=0 --set "sim.integrator=\"$m\""; done
