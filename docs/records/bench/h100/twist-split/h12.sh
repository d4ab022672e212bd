#!/bin/bash
# Newton's cloth_twist against msdsim's twist preset in one lease: b = d954a72's tree,
# c = the truncation's note pass split among 8 lanes, e = find, apply and note split (per stage).
set -u
cp .gl/nw2/part02 /tmp/nw/ && cd /tmp/nw && cat part0* | xz -d | tar x && cd - >/dev/null
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
nvidia-smi --query-gpu=name --format=csv,noheader
m() { b=$1; shift; echo "== msdsim_$b twist $*"; timeout 90 /tmp/nw/msdsim_$b simulate --preset presets/twist.toml --frames 300 --quiet "$@" 2>&1 | grep -E "GPU frame|error" | cut -c1-160; }
m e; m b
PYTHONPATH=/tmp/nw/site timeout 300 python3 .gl/nw2/bench_twist.py --quiet --repeats 2 2>&1 | grep -E "RESULT|Error|error" | head -20
m e; m e --set sim.iterations=4 --set sim.max_strain=0
