#!/bin/bash
# Contact notes (PAIR_MAX) 8, 32 and 64, A/B in one lease: msdsim (8, main e1e7e72),
# msdsim32 and msdsim64 (the same with glsl/contact.comp and src/sim/gpu/contact.rs PAIR_MAX
# changed), stripped release builds carried in .gl/ with stack8.toml and poker52.toml from
# ../shared/peer/. Run from the repository root on the H200.
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
edges=""; for k in 0 1 2 3 4 5 6 7; do edges="$edges --set cloth.$k.self_contact=triangles_and_edges"; done
run() { B=$1; shift; echo "== $B $*" | cut -c1-80; .gl/$B simulate "$@" --quiet 2>&1 | grep -E "GPU frame|error" ; }
for B in msdsim64 msdsim32 msdsim; do run $B --preset .gl/stack8.toml --frames 200 $edges; done
for B in msdsim64 msdsim32 msdsim; do run $B --preset .gl/stack8.toml --frames 200; done
for B in msdsim64 msdsim; do run $B --preset .gl/poker52.toml --frames 120; done
for B in msdsim64 msdsim32; do .gl/$B bench --filter "8 cloths 32x32, inter" --out $OUT/b$B 2>&1 | grep "^| 8"; done
