#!/bin/bash
for f in .gl/c5/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
chmod +x .gl/c5/msdsim_*
nvidia-smi --query-gpu=name --format=csv,noheader
g() { grep -E "GPU frame|GPU stage|error" | cut -c1-160; }
for r in 1 2; do
  for b in head perstage noedges; do echo "== drape $b $r"; timeout 120 .gl/c5/msdsim_$b simulate --preset presets/drape.toml --frames 300 --quiet 2>&1 | g; done
  echo "== drape with a sphere for the form, head $r"; timeout 120 .gl/c5/msdsim_head simulate --preset .gl/c5/drape_sphere.toml --frames 300 --quiet 2>&1 | g
done
