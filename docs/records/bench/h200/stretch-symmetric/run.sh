#!/bin/bash
# A/B of the stretch limit's change: old = 2bbdc63, new = HEAD; interleaved, two rounds.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
chmod +x .gl/msdsim_old .gl/msdsim_new
for r in 1 2; do for b in old new; do
  ./.gl/msdsim_$b bench --frames 300 --filter "curtain 50x50, all features" --out $OUT/$b-curtain-$r > $OUT/$b-curtain-$r.log 2>&1
  ./.gl/msdsim_$b bench --frames 300 --filter "springs only" --cloth-sizes 1024 --rope-sizes 256 --out $OUT/$b-springs-$r > $OUT/$b-springs-$r.log 2>&1
done; done
for f in $OUT/*/bench.md; do echo "== $f"; grep -E "^\|" $f | head -14; done
