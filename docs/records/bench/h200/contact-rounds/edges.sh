#!/bin/bash
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
run() { echo "== $*" | cut -c1-100; .gl/msdsim_rounds simulate "$@" --quiet 2>&1 | grep -E "GPU frame|GPU stage|error|contact between" ; }
for round in 1 2; do
  run --preset .gl/stack8.toml --frames 230
  run --preset .gl/stack8.toml --frames 230 --set sim.inter_object_edges=false
  run --preset .gl/poker52.toml --frames 120
  run --preset .gl/poker52.toml --frames 120 --set sim.inter_object_edges=false
  run --preset .gl/stack8.toml --frames 230 --set sim.iterations=5
done
