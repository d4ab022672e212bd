#!/bin/bash
# Same session: the contact lists' skin (LIST_SKIN in glsl/include/lists.glsl) at 0.5, 1 (the build), 1.5 and 2
# times the contact distance, with bench --shaders (exp/sh_skinX: glsl/ of 2049f7d with LIST_SKIN edited).
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/skin; mkdir -p $R
for r in r1 r2; do for v in base skin05 skin15 skin2; do
  S=""; [ $v != base ] && S="--shaders exp/sh_$v"
  .gl/msdsim bench --frames 1000 --warmup 100 --cloth-sizes 50 --rope-sizes 256 --filter "all features" $S --out $R/p-$r-$v > /dev/null 2>&1 || echo "FAIL p $v"
  grep "all features" $R/p-$r-$v/bench.md | awk -v r="$r $v" -F'|' '{print r, $2, $4, $5, $6}'
  .gl/msdsim bench --frames 200 --warmup 30 --cloth-sizes 32,50,256,1024 --rope-sizes 256 --filter "+ self-collision" $S --out $R/m-$r-$v > /dev/null 2>&1 || echo "FAIL m $v"
  grep "self-collision" $R/m-$r-$v/bench.md | awk -v r="$r $v" -F'|' '{print r, $2, $4, $5, $6}'
  .gl/msdsim bench --frames 200 --warmup 30 --cloth-sizes 50 --rope-sizes 256 --filter "+ self-collision" --per-stage $S --out $R/s-$r-$v > /dev/null 2>&1 || echo "FAIL s $v"
  grep "self-collision" $R/s-$r-$v/bench.md | awk -v r="$r $v per-stage" -F'|' '{print r, $2, $4, $5, $6}'
done; done
tar czf $OUT/skin.tgz -C /tmp skin
