#!/bin/bash
# Same session: the hash scan in one dispatch (.gl/msdsim) against the three-dispatch scan
# (.gl/msdsim-head, 552a21b). Run from the repository root on the GPU machine with .gl/ carried.
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/scan; mkdir -p $R
for r in r1 r2; do for b in head new; do
  B=.gl/msdsim; [ $b = head ] && B=.gl/msdsim-head
  $B bench --frames 200 --warmup 30 --cloth-sizes 256,1024 --rope-sizes 65536 --filter "self-collision" --out $R/m-$r-$b > /dev/null 2>&1 || echo "FAIL m $b"
  grep "1024x1024\|256x256\|65536" $R/m-$r-$b/bench.md | awk -v r="$r $b" -F'|' '{print r, $2, $5, $6, $11, $12}'
  $B bench --frames 200 --warmup 30 --filter "8 cloths" --out $R/k-$r-$b > /dev/null 2>&1 || echo "FAIL k $b"
  grep "8 cloths" $R/k-$r-$b/bench.md | awk -v r="$r $b" -F'|' '{print r, $2, $5, $6}'
done; done
tar czf $OUT/scan.tgz -C /tmp scan
