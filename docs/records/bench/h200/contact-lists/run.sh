#!/bin/bash
# Contact lists between objects, A/B in one lease: msdsim_base (main before the lists) and
# msdsim_new (with them), stripped release builds carried in .gl/ with stack8.toml and
# poker52.toml from ../shared/peer/. Run from the repository root on the H200; two rounds,
# interleaved.
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
edges=""; for k in 0 1 2 3 4 5 6 7; do edges="$edges --set cloth.$k.self_contact=triangles_and_edges"; done
run() { B=$1; shift; echo "== $B $*" | cut -c1-90; .gl/$B simulate "$@" --quiet 2>&1 | grep -E "GPU frame|error|contact between" ; }
for round in 1 2; do
  for B in msdsim_new msdsim_base; do run $B --preset .gl/stack8.toml --frames 200 $edges; done
  for B in msdsim_new msdsim_base; do run $B --preset .gl/stack8.toml --frames 200; done
  for B in msdsim_new msdsim_base; do run $B --preset .gl/poker52.toml --frames 120; done
done
for B in msdsim_new msdsim_base; do run $B --preset presets/rope_on_cloth.toml --frames 300; done
for B in msdsim_new msdsim_base; do .gl/$B bench --filter "8 cloths 32x32, inter" --out $OUT/b$B 2>&1 | grep "^| 8"; done
