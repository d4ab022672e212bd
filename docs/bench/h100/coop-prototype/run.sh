#!/bin/bash
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/coop; mkdir -p $R
for G in 0 1 4 8 16 32 64 128; do
  MSDSIM_COOP=$G timeout 60 .gl/msdsim-coop bench --frames 200 --warmup 30 --cloth-sizes 50,128,256 --rope-sizes 256 --filter "springs only" --per-stage --out $R/g$G > $R/log-$G 2>&1 || { echo "FAIL $G"; tail -3 $R/log-$G; }
  grep "springs only" $R/g$G/bench.md | awk -v r="G=$G" -F'|' '{print r, $2, $5, $6}'
  MSDSIM_COOP=$G timeout 60 .gl/msdsim-coop bench --frames 200 --warmup 30 --cloth-sizes 50 --rope-sizes 256 --filter "without self" --per-stage --out $R/c$G > $R/logc-$G 2>&1 || { echo "FAIL c $G"; tail -3 $R/logc-$G; }
  grep "without self" $R/c$G/bench.md | awk -v r="G=$G" -F'|' '{print r, $2, $5, $6}'
done
tar czf $OUT/coop.tgz -C /tmp coop
