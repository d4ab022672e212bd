#!/bin/bash
# Contact lists between objects, fifth lease: a cloth particle's search split among lanes,
# MSDSIM_EDGE_LANES where cloths keep their edges apart, MSDSIM_CLOTH_LANES otherwise (an
# experiment build's variables; the landed build has the chosen counts as constants).
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
edges=""; for k in 0 1 2 3 4 5 6 7; do edges="$edges --set cloth.$k.self_contact=triangles_and_edges"; done
run() { echo "== $* " | cut -c1-100; env "$@" --quiet 2>&1 | grep -E "GPU frame|error|contact between" ; }
for L in 1 4 8 16 32; do run MSDSIM_EDGE_LANES=$L .gl/msdsim_new simulate --preset .gl/stack8.toml --frames 200 $edges; done
for L in 1 8 16; do MSDSIM_EDGE_LANES=$L .gl/msdsim_new bench --filter "8 cloths 32x32, inter-object contact, edges" --out $OUT/e$L 2>&1 | grep "^| 8"; done
for L in 1 4 8; do run MSDSIM_CLOTH_LANES=$L .gl/msdsim_new simulate --preset .gl/stack8.toml --frames 200; done
for L in 1 4 8; do run MSDSIM_CLOTH_LANES=$L .gl/msdsim_new simulate --preset .gl/poker52.toml --frames 120; done
for L in 1 4 8; do MSDSIM_CLOTH_LANES=$L .gl/msdsim_new bench --filter "8 cloths 32x32, inter-object contact" --out $OUT/c$L 2>&1 | grep "^| 8" | grep -v edges; done
