#!/bin/bash
# Issue 68 on the H200: the stiff-cloth table with c090be1 (start towards rest), then an A/B of
# the predict pass's cost: old = 7f4847e (integrators as before), new = c090be1; two rounds.
for f in .gl/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
chmod +x .gl/msdsim_new .gl/msdsim_start
mv .gl/msdsim_new .gl/msdsim_old7
nvidia-smi --query-gpu=name --format=csv,noheader
time scripts/stiff-cloth.sh .gl/msdsim_start docs/records/accuracy/stiff/stiff-cloth.toml $OUT/stiff > /dev/null 2>&1
python3 scripts/stiff-cloth.py $OUT/stiff > $OUT/table.md 2>&1
tail -20 $OUT/table.md
for r in 1 2; do for b in old7 start; do for m in vbd implicit; do
  ./.gl/msdsim_$b bench --frames 300 --integrator $m --filter "curtain 50x50, all features" --out $OUT/$b-$m-curtain-$r > $OUT/$b-$m-curtain-$r.log 2>&1
  ./.gl/msdsim_$b bench --frames 300 --integrator $m --filter "springs only" --cloth-sizes 1024 --rope-sizes 256 --out $OUT/$b-$m-springs-$r > $OUT/$b-$m-springs-$r.log 2>&1
done; done; done
for f in $OUT/*/bench.md; do echo "== $f"; grep -E "^\|" $f | grep -v "^|--" | head -6; done
