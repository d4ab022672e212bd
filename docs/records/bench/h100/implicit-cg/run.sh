#!/bin/bash
# Same session on the H100: the implicit method by Newton steps of conjugate gradients (this
# build, .gl/msdsim-new) against projective dynamics (the build of a7bebdd, .gl/msdsim-base),
# fused (32 x 32 cloth, 256-node rope) and per stage (256 x 256 and 1024 x 1024 cloths, 65,536-
# node rope), springs only, 4 and 10 iterations, three interleaved runs; Verlet for scale.
# (VBD's A/B: vbd.sh.)
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/icg; mkdir -p $R
bench() {  # NAME BINARY ARGS...
  local name=$1 bin=$2; shift 2
  $bin bench --frames 200 --warmup 30 --filter "springs only" "$@" --out $R/$name > /dev/null 2>&1 || echo "FAIL $name"
  grep "springs only" $R/$name/bench.md | awk -v r="$name" -F'|' '{print r, $2, $5, $6}'
}
for r in r1 r2 r3; do
  for b in base new; do
    for it in 4 10; do
      bench f-$r-$b-$it .gl/msdsim-$b --cloth-sizes 32 --rope-sizes 256 --integrator implicit --iterations $it
      bench p-$r-$b-$it .gl/msdsim-$b --cloth-sizes 256,1024 --rope-sizes 65536 --integrator implicit --iterations $it
    done
  done
done
bench verlet .gl/msdsim-new --cloth-sizes 32 --rope-sizes 256 --integrator verlet
tar czf $OUT/implicit-cg.tgz -C /tmp icg
