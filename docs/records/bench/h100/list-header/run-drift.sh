#!/bin/bash
# Same session, bench --shaders: sh_hdr2 (list headers in registers) against sh_drift (+ the
# lists' moves measured against the object's mean displacement), three interleaved runs:
# the curtain's cases, the small self-colliding cloths and rope; then the matrix's other
# self-collision sizes once each.
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=.gl/msdsim; R=/tmp/drift; mkdir -p $R
for r in r1 r2 r3; do for v in hdr2 drift; do
  $B bench --frames 1000 --warmup 100 --cloth-sizes 32,50 --rope-sizes 256 --shaders exp/sh_$v --out $R/$r-$v > /dev/null 2>&1 || echo "FAIL $r $v"
  grep "curtain\|self-collision\|springs only" $R/$r-$v/bench.md | awk -v r="$r $v" -F'|' '{print r, $2, $4, $5, $6}'
done; done
for v in hdr2 drift; do
  $B bench --frames 300 --warmup 2000 --cloth-sizes 50 --rope-sizes 256 --filter "curtain 50x50, all features" --shaders exp/sh_$v --out $R/settled-$v > /dev/null 2>&1 || echo "FAIL settled $v"
  grep "curtain 50x50, all features |" $R/settled-$v/bench.md | awk -v r="settled $v" -F'|' '{print r, $2, $4, $5, $6}'
done
tar czf $OUT/drift.tgz -C /tmp drift
