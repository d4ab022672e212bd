#!/bin/bash
# Issue 68: the stability maps again with 1799ed1 (the adaptive methods' start towards rest on
# held objects), at the preset's 10 iterations and at 1, on the H200.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
chmod +x .gl/msdsim_head
time ./.gl/msdsim_head stability --out $OUT/stability > $OUT/stability.log 2>&1
for m in xpbd implicit vbd xpbd_jacobi; do
  ./.gl/msdsim_head stability --methods $m --set sim.iterations=1 --out $OUT/stability-1-$m > $OUT/stability-1-$m.log 2>&1
done
tail -5 $OUT/stability.log
for f in $OUT/stability/stability.csv $OUT/stability-1-*/stability.csv; do echo "== $f"; grep "stable in" $f; done
