#!/bin/bash
# Mesh colliders on the GPU: the drape preset's cost, and the existing presets with and
# without the change (53eb563 against HEAD; the mesh test is compiled out where no mesh is).
for f in .gl/c4/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
chmod +x .gl/c4/msdsim_*
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
g() { grep -E "GPU frame|GPU stage|error" | cut -c1-160; }
for r in 1 2 3; do
  for p in curtain tablecloth towel; do
    for b in base mesh; do echo "== $p $b $r"; timeout 60 .gl/c4/msdsim_$b simulate --preset presets/$p.toml --frames 300 --quiet 2>&1 | g; done
  done
done
for r in 1 2 3; do echo "== drape $r"; timeout 120 .gl/c4/msdsim_mesh simulate --preset presets/drape.toml --frames 300 --quiet 2>&1 | g; done
