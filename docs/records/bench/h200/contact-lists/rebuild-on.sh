#!/bin/bash
# After the fix that rebuilds the lists when they come back on (built at infinity while off):
# the scenes of edges-default.sh and rope_on_cloth, once each.
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
edges=""; for k in 0 1 2 3 4 5 6 7; do edges="$edges --set cloth.$k.self_contact=triangles_and_edges"; done
run() { echo "== $*" | cut -c1-120; .gl/msdsim_new simulate "$@" --quiet 2>&1 | grep -E "GPU frame|error|contact between" ; }
run --preset .gl/stack8.toml --frames 230
run --preset .gl/stack8.toml --frames 230 $edges
run --preset .gl/poker52.toml --frames 120
run --preset presets/rope_on_cloth.toml --frames 300
.gl/msdsim_new bench --filter "8 cloths 32x32, inter" --out $OUT/bench 2>&1 | grep "^| 8"
