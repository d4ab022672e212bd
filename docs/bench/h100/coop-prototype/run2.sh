#!/bin/bash
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/coop2; mkdir -p $R
for v in base synconly nocoh; do for G in 2 8 16 64; do
  S=""; [ $v != base ] && S="--shaders exp/sh_$v"
  MSDSIM_COOP=$G timeout 60 .gl/msdsim-coop bench --frames 200 --warmup 30 --cloth-sizes 50 --rope-sizes 256 --filter "without self" --per-stage $S --out $R/c$v$G > $R/logc-$v$G 2>&1 || { echo "FAIL c $v $G"; tail -3 $R/logc-$v$G; }
  grep "without self" $R/c$v$G/bench.md | awk -v r="$v G=$G" -F'|' '{print r, $2, $5, $6}'
done; done
