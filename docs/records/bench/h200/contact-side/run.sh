#!/bin/bash
# Contact between objects pushing a pair that crossed within a substep back to the side it
# began on (msdsim_gap) against main before it (msdsim_e4, e4ac758: the same contact code as
# 6b0b7e1's). H200: the poker cards' stack at frame 30 (before the sphere reaches it; 52 cards
# of 0.4 mm margin should stand 41.6 mm) and the frame times, two rounds.
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
full=""; for k in 0 1 2 3 4 5 6 7; do
  full="$full --set cloth.$k.self_collision=true --set cloth.$k.self_contact=triangles_and_edges"; done
run() { B=$1; shift; echo "== $B $*" | cut -c1-120; .gl/$B simulate "$@" --quiet 2>&1 | grep -E "GPU frame|GPU stage|error|contact between" ; }
for B in msdsim_e4 msdsim_gap; do
  for F in 30 120; do
    .gl/$B simulate --preset .gl/poker52.toml --frames $F --quiet --out $OUT/$B-poker-$F.json 2>&1 | grep -E "error"
  done
  .gl/$B simulate --preset .gl/poker52.toml --frames 30 --quiet --set sim.substeps=160 --set sim.iterations=1 --out $OUT/$B-poker-160x1-30.json 2>&1 | grep error
done
python3 .gl/stack.py $OUT/*poker*.json
for round in 1 2; do
  for B in msdsim_e4 msdsim_gap; do
    run $B --preset .gl/poker52.toml --frames 120
    run $B --preset .gl/stack8.toml --frames 230
    run $B --preset .gl/stack8.toml --frames 230 $full
    run $B --preset presets/rope_on_cloth.toml --frames 200
  done
done
for B in msdsim_e4 msdsim_gap; do
  .gl/$B bench --filter "8 cloths" --out $OUT/bench-$B 2>&1 | grep "^| 8"
done
