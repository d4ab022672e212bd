#!/bin/bash
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
chmod +x .gl/msdsim_*
run() { B=$1; shift; echo "== $B $*"; ./.gl/$B simulate "$@" --quiet 2>&1 | grep -E "GPU frame|GPU stage|error|contact between" | cut -c1-200; }
for r in 1 2; do for B in msdsim_head msdsim_gate; do
run $B --preset .gl/stack8.toml --frames 230
run $B --preset .gl/poker52.toml --frames 120
run $B --preset presets/towel.toml --frames 300
done; done
for B in msdsim_head msdsim_gate; do
./.gl/$B simulate --preset .gl/poker52.toml --frames 30 --quiet --out /tmp/$B-poker.json 2>&1 | grep error
./.gl/$B simulate --preset .gl/stack8.toml --frames 230 --quiet --out /tmp/$B-stack8.json 2>&1 | grep error
done
python3 docs/records/bench/h200/contact-rounds/stack.py /tmp/*poker.json
python3 docs/records/bench/h200/contact-rounds/layers.py /tmp/*stack8.json
for B in msdsim_head msdsim_gate; do ./.gl/$B bench --frames 300 --filter "8 cloths" --out /tmp/bench-$B 2>&1 | grep "^| 8"; done
