#!/bin/bash
# Contact lists between objects (and self-contact's) forced on or off against the policy, on
# the stack with and without edges: an experiment build reading MSDSIM_FORCE_LISTS.
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
edges=""; for k in 0 1 2 3 4 5 6 7; do edges="$edges --set cloth.$k.self_contact=triangles_and_edges"; done
run() { echo "== $*" | cut -c1-100; env "$@" --quiet 2>&1 | grep -E "GPU frame|error|contact between" ; }
for F in policy 1 0; do
  run MSDSIM_FORCE_LISTS=$F .gl/msdsim_new simulate --preset .gl/stack8.toml --frames 230 $edges
  run MSDSIM_FORCE_LISTS=$F .gl/msdsim_new simulate --preset .gl/stack8.toml --frames 230
  run MSDSIM_FORCE_LISTS=$F .gl/msdsim_new simulate --preset .gl/poker52.toml --frames 120
done
echo "== per frame, edges, policy"
.gl/msdsim_new simulate --preset .gl/stack8.toml --frames 230 $edges 2>&1 | grep -E "^frame" | sed -n '1,20p;60,75p;125,145p'
