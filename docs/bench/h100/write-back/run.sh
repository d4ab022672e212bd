#!/bin/bash
# Same session, bench --shaders: sh_base (glsl/ of 504160f), sh_last (the last iteration's
# write-back left out), sh_elide (+ the prediction's two barriers left out after the first
# substep for the iterative methods that stage no velocities). Then a determinism check:
# the final state of a 20 x 20 curtain after 20 frames, each variant against sh_base.
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=.gl/msdsim; R=/tmp/last; mkdir -p $R
for r in r1 r2; do for mi in "verlet 1" "xpbd_jacobi 1" "xpbd_jacobi 4" "implicit 4" "xpbd 1" "vbd 4"; do
  set -- $mi
  for v in base last elide; do
    $B bench --frames 200 --warmup 30 --cloth-sizes 32 --rope-sizes 256 --filter "springs only" --integrator $1 --iterations $2 --shaders exp/sh_$v --out $R/$r-$1-$2-$v > /dev/null 2>&1 || echo "FAIL $r $1 $2 $v"
    grep "springs only" $R/$r-$1-$2-$v/bench.md | awk -v r="$r $1-$2 $v" -F'|' '{print r, $2, $5, $6}'
  done
done; done
for m in implicit xpbd_jacobi xpbd vbd; do for v in base last elide; do
  $B simulate --preset presets/curtain.toml --frames 20 --set sim.integrator=$m --set sim.iterations=3 --set "cloth.curtain.resolution=[20,20]" --quiet --shaders exp/sh_$v --out $R/st-$m-$v.json > /dev/null 2>&1 || echo "FAIL sim $m $v"
done; cmp $R/st-$m-base.json $R/st-$m-last.json && cmp $R/st-$m-base.json $R/st-$m-elide.json && echo "$m: identical"; done
tar czf $OUT/last.tgz -C /tmp last
