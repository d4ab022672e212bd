#!/bin/bash
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
chmod +x .gl/msdsim_*
run() { echo "== P=$MSDSIM_PROBE $*"; ./.gl/msdsim_probe simulate "$@" --quiet 2>&1 | grep -E "GPU frame|GPU stage|error|contact between" | cut -c1-200; }
for P in 0 1 3 7 15 31; do MSDSIM_PROBE=$P run --preset .gl/stack8.toml --frames 230; done
MSDSIM_PROBE=0 run --preset .gl/stack8.toml --frames 230 --set sim.inter_object=false
MSDSIM_PROBE=0 run --preset .gl/stack8.toml --frames 230 --set sim.iterations=1
MSDSIM_PROBE=31 run --preset .gl/stack8.toml --frames 230 --set sim.iterations=1
for P in 0 1 3 31; do MSDSIM_PROBE=$P run --preset .gl/poker52.toml --frames 120; done
MSDSIM_PROBE=0 run --preset .gl/poker52.toml --frames 120 --set sim.inter_object=false
MSDSIM_PROBE=0 run --preset .gl/poker52.toml --frames 120 --set sim.iterations=1
