#!/usr/bin/env bash
# Coulomb friction, momentum-conserving contact between objects (two contact passes) and
# colliders against edges, against the build before them (ab29a68), interleaved A/B, twice.
# On the GPU machine, from the project root, with .gl/msdsim (this build) and .gl/msdsim-old
# (ab29a68), both stripped release binaries.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
for run in 1 2; do
  for build in old new; do
    bin=.gl/msdsim; [ $build = old ] && bin=.gl/msdsim-old
    $bin bench --frames 200 --warmup 30 --filter "curtain 50x50" --out "$out/curtain-$build-$run" > /dev/null
    $bin bench --frames 200 --warmup 30 --filter "8 cloths" --out "$out/contact-$build-$run" > /dev/null
    $bin bench --frames 200 --warmup 30 --cloth-sizes 1024 --rope-sizes 256 --filter "1024x1024" --out "$out/cloth1024-$build-$run" > /dev/null
  done
done
tar -C "$(dirname "$out")" -cf "${OUT:-/tmp/out}/runs.tar" runs
