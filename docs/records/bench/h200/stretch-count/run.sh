#!/bin/bash
# The stretch limit's counts (issue 69, item 10): old = c870e9e (each end its own share),
# new = the count pass / fused count phase; interleaved, two rounds, as
# docs/records/bench/h200/stretch-symmetric/run.sh measured the reverted try.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
chmod +x .gl/msdsim_sold .gl/msdsim_snew
for r in 1 2; do for b in sold snew; do
  ./.gl/msdsim_$b bench --frames 300 --filter "curtain 50x50, all features" --out $OUT/$b-curtain-$r > $OUT/$b-curtain-$r.log 2>&1
  ./.gl/msdsim_$b bench --frames 300 --filter "springs only" --cloth-sizes 1024 --rope-sizes 256 --out $OUT/$b-springs-$r > $OUT/$b-springs-$r.log 2>&1
done; done
for f in $OUT/*/bench.md; do echo "== $f"; grep -E "^\|" $f | head -14; done
