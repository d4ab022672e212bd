#!/bin/bash
# Side by side on the H200 in one lease: Newton 1.8's VBD on the 8-cloth stack with
# self-contact (bench_stack.py, CUDA events around one CUDA graph a frame) and msdsim 4551ae5
# (contact rounds) on the same stack (stack8.toml, every cloth's self-contact with edges, and
# contact between objects alone), interleaved, two rounds.
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
cd /tmp/nw && cat part0* | xz -d | tar x && cd - > /dev/null
full=""; for k in 0 1 2 3 4 5 6 7; do
  full="$full --set cloth.$k.self_collision=true --set cloth.$k.self_contact=triangles_and_edges"; done
for round in 1 2; do
  echo "== Newton round $round"
  PYTHONPATH=/tmp/nw/site timeout 280 python3 ../shared/peer/bench_stack.py --selfcontact 1 2>&1 | grep -E "RESULT|Error|error" | tail -3
  echo "== msdsim full, round $round"
  .gl/msdsim_rounds simulate --preset .gl/stack8.toml --frames 230 --quiet $full 2>&1 | grep -E "GPU frame|error"
  echo "== msdsim between objects, round $round"
  .gl/msdsim_rounds simulate --preset .gl/stack8.toml --frames 230 --quiet 2>&1 | grep -E "GPU frame|error"
done
