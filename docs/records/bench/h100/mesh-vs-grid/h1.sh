set -u
nvidia-smi --query-gpu=name --format=csv,noheader
for f in .gl/c1/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
cd .gl/c1
B=./msdsim_x
run() { echo "== $*"; nvidia-smi --query-gpu=name --format=csv,noheader 2>/dev/null | head -1 >/dev/null; $B simulate "$@" --frames 200 --quiet 2>&1 | grep -E "GPU frame time|stage means|error"; }
for rep in 1 2 3; do
  for p in grid quads tris; do run --preset $p.toml; done
done
for rep in 1 2; do
  for p in grid quads tris; do
    run --preset $p.toml --set 'sim.integrator="symplectic_euler"' --set sim.substeps=32 --set $( [ $p = grid ] && echo cloth || echo mesh_cloth ).0.stiffness.structural=40
  done
done
run --preset ../../presets/holed_flag.toml
run --preset ../../presets/flag.toml
run --preset skirt.toml
run --preset skirt.toml --set mesh_cloth.0.self_collision=false
run --preset skirt.toml
run --preset skirt.toml --set mesh_cloth.0.self_collision=false
run --preset ../../presets/drape.toml
