#!/bin/bash
# Contact between objects after the lists and the cloth lanes (adaf6ba), side by side with
# NVIDIA Newton 1.8 (warp-lang 1.19) in one lease: newton_stack.py is
# ../shared/peer/bench_stack.py (Newton's VBD, self-contact with edges, 200 frames after 30).
# Newton's site packages were sent in three parts to /tmp/nw before this call.
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
export PYTHONPATH=/tmp/nw/site
here=docs/records/bench/h200/contact-lists
edges=""; for k in 0 1 2 3 4 5 6 7; do edges="$edges --set cloth.$k.self_contact=triangles_and_edges"; done
run() { echo "== $*" | cut -c1-100; .gl/msdsim_new simulate "$@" --quiet 2>&1 | grep -E "GPU frame|error|contact between" ; }
for round in 1 2; do
  echo "== newton stack, self-contact"; python3 $here/newton_stack.py --selfcontact 1 2>&1 | grep RESULT
  run --preset .gl/stack8.toml --frames 230 $edges
  run --preset .gl/stack8.toml --frames 230
done
echo "== newton stack, no contact"; python3 $here/newton_stack.py --selfcontact 0 2>&1 | grep RESULT
run --preset .gl/poker52.toml --frames 120
.gl/msdsim_new simulate --preset .gl/stack8.toml --frames 230 $edges 2>&1 | grep -E "^frame" | awk 'NR%10==0' | head -30
.gl/msdsim_new bench --filter "8 cloths" --out $OUT/bench 2>&1 | grep "^| 8"
