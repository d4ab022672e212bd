#!/bin/bash
# Same session: the locality hash (.gl/msdsim) against the build before it (.gl/msdsim-head,
# 2edde19). Run from the repository root on the GPU machine with .gl/ carried.
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /tmp/r44
for r in r1 r2; do for b in head new; do
  B=.gl/msdsim; [ $b = head ] && B=.gl/msdsim-head
  $B bench --frames 200 --warmup 30 --cloth-sizes 50,256,1024 --rope-sizes 256,65536 --out /tmp/r44/m-$r-$b > /dev/null 2>&1 || echo "FAIL m $b"
  grep "1024x1024\|256x256\|65536\|50x50, + self\|50x50, springs\|curtain" /tmp/r44/m-$r-$b/bench.md | awk -v r="$r $b" -F'|' '{print r, $2, $4, $5, $6, $11, $12}'
  $B bench --frames 1000 --warmup 100 --cloth-sizes 50 --rope-sizes 256 --filter "all features" --out /tmp/r44/p-$r-$b > /dev/null 2>&1 || echo "FAIL p $b"
  grep "all features" /tmp/r44/p-$r-$b/bench.md | awk -v r="$r $b paper" -F'|' '{print r, $2, $5, $6}'
  $B bench --frames 200 --warmup 30 --filter "8 cloths" --out /tmp/r44/k-$r-$b > /dev/null 2>&1 || echo "FAIL k $b"
  grep "8 cloths" /tmp/r44/k-$r-$b/bench.md | awk -v r="$r $b" -F'|' '{print r, $2, $5, $6}'
done; done
tar czf $OUT/r44.tgz -C /tmp r44
