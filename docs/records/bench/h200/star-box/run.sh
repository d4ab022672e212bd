#!/bin/bash
# Contact between objects: star-box filter and batched contact passes (msdsim_new) against
# main 3bc50b6 (msdsim_base, frames identical to 365e329's); msdsim_new with --shaders
# .gl/nobox is the batched passes alone (the box test compiled out). H200, two rounds.
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
full=""; for k in 0 1 2 3 4 5 6 7; do
  full="$full --set cloth.$k.self_collision=true --set cloth.$k.self_contact=triangles_and_edges"; done
run() { B=$1; shift; echo "== $B $*" | cut -c1-120; .gl/$B simulate "$@" --quiet 2>&1 | grep -E "GPU frame|GPU stage|error|contact between" ; }
for round in 1 2; do
  run msdsim_base --preset .gl/poker52.toml --frames 120
  run msdsim_new --preset .gl/poker52.toml --frames 120
  run msdsim_new --preset .gl/poker52.toml --frames 120 --shaders .gl/nobox
  for B in msdsim_base msdsim_new; do
    run $B --preset .gl/stack8.toml --frames 230
    run $B --preset .gl/stack8.toml --frames 230 $full
    run $B --preset presets/rope_on_cloth.toml --frames 200
  done
done
for B in msdsim_base msdsim_new; do
  .gl/$B bench --filter "8 cloths" --out $OUT/bench-$B 2>&1 | grep "^| 8"
done
for P in .gl/poker52.toml .gl/stack8.toml presets/rope_on_cloth.toml; do
  n=$(basename $P .toml)
  for B in msdsim_base msdsim_new; do
    mkdir -p /tmp/$B; .gl/$B simulate --preset $P --frames 40 --quiet --record /tmp/$B/$n.pc2 2>&1 | grep -E "error"
    echo "$n $B $(cat /tmp/$B/${n}_*.pc2 | md5sum)"
  done
done
