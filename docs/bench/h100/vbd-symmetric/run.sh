#!/bin/bash
# Same session: VBD with the symmetric Hessian (exp/sh_vbdsym: glsl/ of the commit after
# 2049f7d, glsl/include/solver_bodies.glsl as committed) against the build of d63b12b (.gl/msdsim), bench --shaders.
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/vbd; mkdir -p $R
for r in r1 r2; do for v in base vbdsym; do
  S=""; [ $v != base ] && S="--shaders exp/sh_$v"
  .gl/msdsim bench --frames 200 --warmup 30 --cloth-sizes 32 --rope-sizes 256 --filter "springs only" --integrator vbd --iterations 4 $S --out $R/f-$r-$v > /dev/null 2>&1 || echo "FAIL f $v"
  grep "springs only" $R/f-$r-$v/bench.md | awk -v r="$r $v fused" -F'|' '{print r, $2, $5, $6}'
  .gl/msdsim bench --frames 200 --warmup 30 --cloth-sizes 256,1024 --rope-sizes 65536 --filter "springs only" --integrator vbd --iterations 4 $S --out $R/p-$r-$v > /dev/null 2>&1 || echo "FAIL p $v"
  grep "springs only" $R/p-$r-$v/bench.md | awk -v r="$r $v" -F'|' '{print r, $2, $5, $6}'
done; done
.gl/msdsim bench --frames 200 --warmup 30 --cloth-sizes 32 --rope-sizes 256 --filter "springs only" --integrator verlet --out $R/verlet > /dev/null 2>&1
grep "springs only" $R/verlet/bench.md | awk -F'|' '{print "verlet", $2, $5, $6}'
tar czf $OUT/vbd.tgz -C /tmp vbd
