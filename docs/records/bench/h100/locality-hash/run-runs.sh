#!/bin/bash
# The per-stage query by runs (exp/sh_runs: glsl/ of 90f8232) against the shaders of ac106f0 (the
# binary .gl/msdsim built from ac106f0), with bench --shaders. Results are in PERFORMANCE.md.
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
for r in r1 r2; do for v in base runs; do
  S=""; [ $v != base ] && S="--shaders exp/sh_$v"
  .gl/msdsim bench --frames 200 --warmup 30 --cloth-sizes 256,1024 --rope-sizes 65536 --filter "self-collision" $S --out /tmp/m-$r-$v > /dev/null 2>&1 || echo "FAIL m $v"
  grep "1024x1024\|256x256\|65536" /tmp/m-$r-$v/bench.md | awk -v r="$r $v" -F'|' '{print r, $2, $5, $6, $11, $12}'
done; done
