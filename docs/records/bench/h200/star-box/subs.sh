#!/bin/bash
# poker52: does the stack of 52 cards hold (its height, and whether the lists stay on) at
# more substeps of fewer iterations?
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
for c in "20 10" "40 5" "80 3" "160 1" "80 10"; do
  set -- $c
  echo "== substeps $1 iterations $2"
  .gl/msdsim_new simulate --preset .gl/poker52.toml --frames 30 --quiet --set sim.substeps=$1 --set sim.iterations=$2 --out $OUT/p30_$1_$2.json 2>&1 | grep -E "GPU frame|error|contact between"
  .gl/msdsim_new simulate --preset .gl/poker52.toml --frames 120 --quiet --set sim.substeps=$1 --set sim.iterations=$2 --out $OUT/p120_$1_$2.json 2>&1 | grep -E "GPU frame|GPU stage|error|contact between"
done
