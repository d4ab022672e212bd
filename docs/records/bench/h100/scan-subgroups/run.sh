#!/bin/bash
# Same session: the hash scan by subgroups (.gl/msdsim) against the three-dispatch scan
# (.gl/msdsim-head, 552a21b); the first run of the subgroup scan, without its steps sized to the
# table, also had .gl/msdsim-a62 (a62f444: one dispatch, strided reads) in the loop below
# (files *-a62.md). Run from the repository root on the GPU machine with .gl/ carried.
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/scan2; mkdir -p $R
for r in r1 r2; do for b in head new; do
  B=.gl/msdsim; [ $b != new ] && B=.gl/msdsim-$b
  $B bench --frames 200 --warmup 30 --cloth-sizes 256,512,1024 --rope-sizes 65536 --filter "self-collision" --out $R/m-$r-$b > /dev/null 2>&1 || echo "FAIL m $b"
  grep "1024x1024\|512x512\|256x256\|65536" $R/m-$r-$b/bench.md | awk -v r="$r $b" -F'|' '{print r, $2, $5, $6, $11, $12}'
  $B bench --frames 200 --warmup 30 --cloth-sizes 50 --rope-sizes 256 --filter "self-collision" --per-stage --out $R/s-$r-$b > /dev/null 2>&1 || echo "FAIL s $b"
  grep "50x50, + self\|rope 256, + self" $R/s-$r-$b/bench.md | awk -v r="$r $b per-stage" -F'|' '{print r, $2, $5, $6}'
  $B bench --frames 200 --warmup 30 --filter "8 cloths" --out $R/k-$r-$b > /dev/null 2>&1 || echo "FAIL k $b"
  grep "8 cloths" $R/k-$r-$b/bench.md | awk -v r="$r $b" -F'|' '{print r, $2, $5, $6}'
done; done
tar czf $OUT/scan2.tgz -C /tmp scan2
