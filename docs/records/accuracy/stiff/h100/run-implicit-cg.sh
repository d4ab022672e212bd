#!/bin/bash
# On the H100 after the implicit method moved to Newton steps of conjugate gradients (build
# .gl/msdsim-new): its runs of the stiff-cloth table (scripts/stiff-cloth.sh, the other methods'
# runs are the earlier ones in runs.tgz), the stiff chart, and every shipped preset with the
# implicit method at 10 iterations for 600 frames (exit codes: 3 would be a guard stop).
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=.gl/msdsim-new
METHODS=implicit VERLET=0 scripts/stiff-cloth.sh $B docs/records/accuracy/stiff/stiff-cloth.toml /tmp/stiff
tar czf $OUT/stiff-implicit.tgz -C /tmp stiff
for p in presets/*.toml; do
  timeout 120 $B simulate --preset $p --frames 600 --quiet --set sim.integrator=implicit --set sim.iterations=10 > /tmp/preset.log 2>&1
  echo "$p: exit $? $(grep -E 'GPU frame time|stopped' /tmp/preset.log | head -2 | tr '\n' ' ')"
done
timeout 300 $B chart --scenes stiff --substeps 1,2,4,8,16,128 --iterations 1,2,4,10,30,100 --reference-substeps 256 --out $OUT/chart-stiff > /dev/null 2>&1 || echo "chart stiff: exit $?"
