#!/bin/bash
# The bench's fused case ("8 cloths 32x32, no contact") and fused presets: main (msdsim_base)
# against the batched build (msdsim_new), and that build with the dynamic indexing feature
# left off (msdsim_skin here: an experiment build reading MSDSIM_NOFEAT).
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
for r in 1 2; do
  .gl/msdsim_base bench --filter "no contact" --out $OUT/b$r 2>&1 | grep "^| "
  .gl/msdsim_new bench --filter "no contact" --out $OUT/n$r 2>&1 | grep "^| "
  MSDSIM_NOFEAT=1 .gl/msdsim_skin bench --filter "no contact" --out $OUT/f$r 2>&1 | grep "^| "
done
for B in msdsim_base msdsim_new; do
  for P in towel curtain; do echo "== $B $P"; .gl/$B simulate --preset presets/$P.toml --frames 300 --quiet 2>&1 | grep "GPU frame"; done
done
