#!/bin/bash
# Where the fused curtain's self-collision goes (timing only: the variants' contacts are
# wrong): sh_hdr2 (the list headers in registers, as committed next), sh_nowalk (no list
# walked), sh_norebuild (lists built once per dispatch's validity and never again), and
# the curtain without self-collision, three interleaved runs.
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=.gl/msdsim; R=/tmp/walk; mkdir -p $R
for r in r1 r2 r3; do for v in hdr2 nowalk norebuild; do
  $B bench --frames 1000 --warmup 100 --cloth-sizes 50 --rope-sizes 256 --filter "curtain 50x50, all features" --shaders exp/sh_$v --out $R/$r-$v > /dev/null 2>&1 || echo "FAIL $r $v"
  grep "curtain 50x50, all features |" $R/$r-$v/bench.md | awk -v r="$r $v" -F'|' '{print r, $2, $4, $5, $6}'
done; done
tar czf $OUT/walk.tgz -C /tmp walk
