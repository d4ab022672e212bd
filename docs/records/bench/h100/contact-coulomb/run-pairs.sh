#!/usr/bin/env bash
# Contact between objects with the count pass noting each particle's partners (the sum pass
# walks them instead of searching the hash again), against ab29a68; interleaved, three runs.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
for run in 1 2 3; do for build in old new; do
  bin=.gl/msdsim; [ $build = old ] && bin=.gl/msdsim-old
  echo "== $build $run"
  $bin bench --frames 200 --warmup 30 --filter "8 cloths" 2>&1 | grep ms/frame
done; done
