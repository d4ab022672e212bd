#!/bin/bash
# Newton's cloth_twist against msdsim's twist preset in the same lease.
cd /tmp/nw && cat part0* | xz -d | tar x && cd - >/dev/null
for f in .gl/c1/*.deb /tmp/nw/*.deb; do [ -f $f ] && dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
N=/tmp/nw/msdsim
nvidia-smi --query-gpu=name --format=csv,noheader
for r in 1 2 3; do echo "== msdsim twist $r"; timeout 60 $N simulate --preset presets/twist.toml --frames 300 --quiet 2>&1 | grep -E "GPU frame|error" | cut -c1-160; done
PYTHONPATH=/tmp/nw/site timeout 400 python3 .gl/c3/bench_twist.py --quiet --repeats 3 2>&1 | grep -E "RESULT|Error|error" | head -20
for r in 4 5; do echo "== msdsim twist $r"; timeout 60 $N simulate --preset presets/twist.toml --frames 300 --quiet 2>&1 | grep -E "GPU frame|error" | cut -c1-160; done
