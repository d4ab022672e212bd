#!/bin/bash
# Self-contact lists' policy (per object): frames off (MSDSIM_SELF_OFF) and the share of a
# frame's substeps rebuilt past which they go off (MSDSIM_SELF_SHARE quarters), experiment build.
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
run() { echo "== $*" | cut -c1-120; env "$@" --quiet 2>&1 | grep -E "GPU frame|error" ; }
for V in "64 1" "16 1" "4 1" "16 3" "4 3"; do set -- $V
  run MSDSIM_SELF_OFF=$1 MSDSIM_SELF_SHARE=$2 .gl/msdsim_new simulate --preset presets/towel.toml --frames 300
  run MSDSIM_SELF_OFF=$1 MSDSIM_SELF_SHARE=$2 .gl/msdsim_new simulate --preset presets/towel.toml --frames 300 --set cloth.towel.self_contact=triangles_and_edges
done
