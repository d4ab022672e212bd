#!/bin/bash
# Contact between objects after every VBD iteration (msdsim_rounds, 4551ae5) against main
# before it (msdsim_gap, a2d22f9). H200: the poker cards' stack at frame 30 (52 cards of
# 0.4 mm margin should stand 41.6 mm), the 8-cloth stack's layer gaps (reach 10 mm), and
# the frame times, two rounds.
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
full=""; for k in 0 1 2 3 4 5 6 7; do
  full="$full --set cloth.$k.self_collision=true --set cloth.$k.self_contact=triangles_and_edges"; done
run() { B=$1; shift; echo "== $B $*" | cut -c1-120; .gl/$B simulate "$@" --quiet 2>&1 | grep -E "GPU frame|GPU stage|error|contact between" ; }
for B in msdsim_gap msdsim_rounds; do
  .gl/$B simulate --preset .gl/poker52.toml --frames 30 --quiet --out $OUT/$B-poker-30.json 2>&1 | grep -E "error"
  .gl/$B simulate --preset .gl/stack8.toml --frames 230 --quiet --out $OUT/$B-stack8.json 2>&1 | grep -E "error"
done
python3 docs/records/bench/h200/contact-rounds/stack.py $OUT/*poker*.json
python3 docs/records/bench/h200/contact-rounds/layers.py $OUT/*stack8.json
for round in 1 2; do
  for B in msdsim_gap msdsim_rounds; do
    run $B --preset .gl/poker52.toml --frames 120
    run $B --preset .gl/stack8.toml --frames 230
    run $B --preset .gl/stack8.toml --frames 230 $full
    run $B --preset presets/rope_on_cloth.toml --frames 200
  done
done
for B in msdsim_gap msdsim_rounds; do
  .gl/$B bench --filter "8 cloths" --out $OUT/bench-$B 2>&1 | grep "^| 8"
done
