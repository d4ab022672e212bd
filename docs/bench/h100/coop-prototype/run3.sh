#!/bin/bash
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/coop3; mkdir -p $R
for v in base vmm; do for G in 8 16 32 64 128; do
  S=""; [ $v != base ] && S="--shaders exp/sh_$v"
  MSDSIM_COOP=$G timeout 60 .gl/msdsim-coop bench --frames 200 --warmup 30 --cloth-sizes 50,128,256 --rope-sizes 256 --filter "springs only" --per-stage $S --out $R/c$v$G > $R/logc-$v$G 2>&1 || { echo "FAIL c $v $G"; tail -3 $R/logc-$v$G; }
  grep "cloth" $R/c$v$G/bench.md | awk -v r="$v G=$G" -F'|' '{print r, $2, $5, $6}'
done; done
