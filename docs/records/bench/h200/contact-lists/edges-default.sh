#!/bin/bash
# Contact between objects keeping cloths' edges apart by default (sim.inter_object_edges):
# the scenes with several cloths, with it (the default) and without.
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
run() { echo "== $*" | cut -c1-120; .gl/msdsim_new simulate "$@" --quiet 2>&1 | grep -E "GPU frame|error|contact between" ; }
for round in 1 2; do
  for E in true false; do
    run --preset .gl/stack8.toml --frames 230 --set sim.inter_object_edges=$E
    run --preset .gl/poker52.toml --frames 120 --set sim.inter_object_edges=$E
  done
done
.gl/msdsim_new bench --filter "8 cloths" --out $OUT/bench 2>&1 | grep "^| 8"
