#!/bin/bash
# The bench's "8 cloths" cases in one process, as the bench runs them, with the chunk capped
# at 64 (the default), 16 and 1 objects (msdsim_skin here: an experiment build of 5d1c260
# reading MSDSIM_CHUNK), against main before the chunks (msdsim_base, 3bc50b6); and the
# poker cards and the stack at each cap.
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
.gl/msdsim_base bench --filter "8 cloths" --out $OUT/base 2>&1 | grep "^| 8"
for C in 64 16 1; do
  echo "== chunk $C"
  MSDSIM_CHUNK=$C .gl/msdsim_skin bench --filter "8 cloths" --out $OUT/c$C 2>&1 | grep "^| 8"
  MSDSIM_CHUNK=$C .gl/msdsim_skin simulate --preset .gl/stack8.toml --frames 230 --quiet 2>&1 | grep "GPU frame"
  MSDSIM_CHUNK=$C .gl/msdsim_skin simulate --preset .gl/poker52.toml --frames 60 --quiet 2>&1 | grep "GPU frame"
done
