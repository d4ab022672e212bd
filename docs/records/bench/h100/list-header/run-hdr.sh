#!/bin/bash
# Same session, bench --shaders: sh_base (glsl/ of 504160f) against sh_hdr (each particle's
# contact-list header kept in registers in the fused kernel, not read from the list buffer
# every substep), three interleaved runs; the curtain's cases and the small self-colliding
# cloths and rope.
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=.gl/msdsim; R=/tmp/hdr; mkdir -p $R
for r in r1 r2 r3; do for v in base hdr; do
  $B bench --frames 1000 --warmup 100 --cloth-sizes 32,50 --rope-sizes 256 --shaders exp/sh_$v --out $R/$r-$v > /dev/null 2>&1 || echo "FAIL $r $v"
  grep "curtain\|self-collision\|springs only" $R/$r-$v/bench.md | awk -v r="$r $v" -F'|' '{print r, $2, $4, $5, $6}'
done; done
tar czf $OUT/hdr.tgz -C /tmp hdr
