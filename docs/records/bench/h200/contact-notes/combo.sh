#!/bin/bash
# 64 notes and owner() by bisection (msdsim_c, main after 70fe1b7) against 32 notes and the
# linear owner() (msdsim32, main 70fe1b7), one lease on the H200.
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
edges=""; for k in 0 1 2 3 4 5 6 7; do edges="$edges --set cloth.$k.self_contact=triangles_and_edges"; done
run() { B=$1; shift; echo "== $B $*" | cut -c1-90; .gl/$B simulate "$@" --quiet 2>&1 | grep -E "GPU frame|error" ; }
for B in msdsim_c msdsim32 msdsim_c; do run $B --preset .gl/poker52.toml --frames 120; done
for B in msdsim_c; do run $B --preset .gl/stack8.toml --frames 200; run $B --preset .gl/stack8.toml --frames 200 $edges; done
.gl/msdsim_c bench --filter "8 cloths 32x32, inter" --out $OUT/b 2>&1 | grep "^| 8"
