#!/bin/bash
# Same session: the spring loop with one inversesqrt (exp/sh_rsqrt: glsl/ as committed) against the
# build of 8ceb930 (.gl/msdsim, length() and a division), bench --shaders, three runs.
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/rs2; mkdir -p $R
for r in r1 r2 r3; do for v in base rsqrt; do for m in verlet symplectic_euler implicit; do
  S=""; [ $v != base ] && S="--shaders exp/sh_$v"
  .gl/msdsim bench --frames 200 --warmup 30 --cloth-sizes 32 --rope-sizes 256 --filter "springs only" --integrator $m --iterations 4 $S --out $R/$r-$v-$m > /dev/null 2>&1 || echo "FAIL $v $m"
  grep "springs only" $R/$r-$v-$m/bench.md | awk -v r="$r $v $m" -F'|' '{print r, $2, $5, $6}'
done; done; done
tar czf $OUT/rs2.tgz -C /tmp rs2
