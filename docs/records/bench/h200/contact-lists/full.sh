#!/bin/bash
# The stack with full contact as Newton runs it: each cloth's self-contact on too
# (stack8.toml has self_collision = false), triangles and edges, then triangles alone.
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
full=""; tri=""; for k in 0 1 2 3 4 5 6 7; do
  full="$full --set cloth.$k.self_collision=true --set cloth.$k.self_contact=triangles_and_edges"
  tri="$tri --set cloth.$k.self_collision=true --set cloth.$k.self_contact=triangles"; done
run() { echo "== $*" | cut -c1-120; .gl/msdsim_new simulate "$@" --quiet 2>&1 | grep -E "GPU frame|GPU stage|error|contact between" ; }
for round in 1 2; do
  run --preset .gl/stack8.toml --frames 230 $full
done
run --preset .gl/stack8.toml --frames 230 $tri
