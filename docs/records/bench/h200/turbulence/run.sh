#!/bin/bash
# The wind's turbulence: its cost on the H200 (msdsim_turb = cd5c6c6), two rounds.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
chmod +x .gl/msdsim_*
run() { echo "== $*" | cut -c1-160; ./.gl/msdsim_turb simulate "$@" --quiet 2>&1 | grep -E "GPU frame|GPU stage|error" | cut -c1-160; }
cw="--set wind.enabled=true --set wind.speed=5 --set wind.origin=[0,1,2] --set wind.direction=[0,0,-1] --set wind.full_force_radius=2 --set wind.reference_distance=2"
big="--set cloth.0.resolution=[1024,1024] --set sim.max_speed=1e6"
for r in 1 2; do
  for t in 0 0.3; do run --preset presets/flag.toml --frames 600 --set wind.turbulence=$t; done
  run --preset presets/flag.toml --frames 600 --set wind.model=paper --set wind.force=0.01
  for t in 0 0.5; do run --preset presets/curtain.toml --frames 600 $cw --set wind.turbulence=$t; done
  for t in 0 0.5; do run --preset presets/curtain.toml --frames 100 $cw $big --set wind.turbulence=$t; done
  for t in 0 0.3; do run --preset presets/flag.toml --frames 100 $big --set wind.turbulence=$t; done
done
