#!/bin/bash
# The full matrix twice, the paper's cases over 1,000 frames twice, and the end-to-end cases, with
# the release binary of this commit (.gl/msdsim). Run from the repository root on the GPU
# machine with .gl/ carried; results in $OUT/full.tgz.
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/full; mkdir -p $R
for r in run1 run2; do
  .gl/msdsim bench --frames 200 --warmup 30 --out $R/$r > $R/$r.log 2>&1 || echo "FAIL $r"
  .gl/msdsim bench --frames 1000 --warmup 100 --cloth-sizes 50 --rope-sizes 256 --filter "all features" --out $R/paper-$r > /dev/null 2>&1 || echo "FAIL paper $r"
done
.gl/msdsim bench --end-to-end --frames 2000 --warmup 200 --out $R/end-to-end > /dev/null 2>&1 || echo "FAIL e2e"
grep "1024x1024\|curtain\|rope 256, all" $R/run1/bench.md | awk -F'|' '{print $2, $4, $5}'
tar czf $OUT/full.tgz -C /tmp full
