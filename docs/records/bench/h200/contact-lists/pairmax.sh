#!/bin/bash
# Contact lists between objects: a particle's list length where cloths keep their edges apart
# (MSDSIM_PAIR_MAX) and the frames the lists stay off once they did not last
# (MSDSIM_OFF_FRAMES), an experiment build reading both (and MSDSIM_FORCE_LISTS).
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
edges=""; for k in 0 1 2 3 4 5 6 7; do edges="$edges --set cloth.$k.self_contact=triangles_and_edges"; done
run() { echo "== $*" | cut -c1-120; env "$@" --quiet 2>&1 | grep -E "GPU frame|error|contact between" ; }
for P in 64 128 256; do
  run MSDSIM_PAIR_MAX=$P MSDSIM_FORCE_LISTS=1 .gl/msdsim_new simulate --preset .gl/stack8.toml --frames 230 $edges
  run MSDSIM_PAIR_MAX=$P .gl/msdsim_new simulate --preset .gl/stack8.toml --frames 230 $edges
done
for O in 64 16 4; do
  run MSDSIM_OFF_FRAMES=$O .gl/msdsim_new simulate --preset .gl/stack8.toml --frames 230
  run MSDSIM_OFF_FRAMES=$O .gl/msdsim_new simulate --preset .gl/poker52.toml --frames 120
  run MSDSIM_OFF_FRAMES=$O MSDSIM_PAIR_MAX=256 .gl/msdsim_new simulate --preset .gl/stack8.toml --frames 230 $edges
  run MSDSIM_OFF_FRAMES=$O .gl/msdsim_new simulate --preset presets/rope_on_cloth.toml --frames 300
done
for O in 64 4; do MSDSIM_OFF_FRAMES=$O MSDSIM_PAIR_MAX=256 .gl/msdsim_new bench --filter "8 cloths 32x32, inter" --out $OUT/b$O 2>&1 | grep "^| 8"; done
