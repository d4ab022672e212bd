#!/bin/bash
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/coop4; mkdir -p $R
for r in r1 r2; do for G in 0 1; do
  MSDSIM_COOP=$G timeout 60 .gl/msdsim-coop bench --frames 200 --warmup 30 --cloth-sizes 50,128,256 --rope-sizes 256 --filter "springs only" --per-stage --out $R/$r-g$G > $R/log-$r-$G 2>&1 || { echo "FAIL $G"; tail -3 $R/log-$r-$G; }
  grep "springs only\|wind\|spheres\|ground" $R/$r-g$G/bench.md | awk -v r="$r coop=$G" -F'|' '{print r, $2, $5, $6}'
  MSDSIM_COOP=$G timeout 60 .gl/msdsim-coop bench --frames 200 --warmup 30 --cloth-sizes 50 --rope-sizes 256 --filter "without self" --per-stage --out $R/$r-c$G > $R/logc-$r-$G 2>&1 || { echo "FAIL c $G"; tail -3 $R/logc-$r-$G; }
  grep "without self" $R/$r-c$G/bench.md | awk -v r="$r coop=$G" -F'|' '{print r, $2, $5, $6}'
done; done
tar czf $OUT/coop4.tgz -C /tmp coop4
