#!/bin/bash
# Contact between objects: owner() by bisection (.gl/v_owner: a copy of glsl/ with contact.comp's owner() as in 2c; --shaders) against the linear
# search built into msdsim32 (main 70fe1b7), A/B in one lease on the H200.
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
edges=""; for k in 0 1 2 3 4 5 6 7; do edges="$edges --set cloth.$k.self_contact=triangles_and_edges"; done
run() { echo "== $*" | cut -c1-90; .gl/msdsim32 simulate "$@" --quiet 2>&1 | grep -E "GPU frame|error" ; }
for r in 1 2; do
for S in "" "--shaders .gl/v_owner"; do run --preset .gl/poker52.toml --frames 120 $S; done
done
for S in "" "--shaders .gl/v_owner"; do run --preset .gl/stack8.toml --frames 200 $S; run --preset .gl/stack8.toml --frames 200 $edges $S; done
