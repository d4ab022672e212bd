#!/usr/bin/env bash
# Aerodynamic wind: its cost against the paper's, and the build before it (d0aee6a, .gl/msdsim-old)
# on the cases the change touches (the physics stage reads Globals.wind_speed in every case).
# On the GPU machine, from the project root, with .gl/msdsim (this build) and .gl/msdsim-old.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
for run in 1 2; do
  for build in old new; do
    bin=.gl/msdsim; [ $build = old ] && bin=.gl/msdsim-old
    $bin bench --frames 200 --warmup 30 --filter "curtain 50x50" --out "$out/curtain-$build-$run" > /dev/null
    $bin bench --frames 100 --warmup 20 --cloth-sizes 1024 --rope-sizes 256 --filter "1024x1024, + wind" --out "$out/wind1024-$build-$run" > /dev/null
  done
  for model in paper aerodynamic; do
    .gl/msdsim simulate --preset presets/flag.toml --set wind.model=$model --set wind.speed=25 \
      --set 'cloth.0.resolution=[512,512]' --frames 300 --quiet > "$out/flag512-$model-$run.txt" 2>&1
  done
done
tar -C "$(dirname "$out")" -cf "${OUT:-/tmp/out}/runs.tar" runs
for f in $out/*/bench.md; do echo "== $f"; grep -E "^\| (curtain 50x50, all features|cloth 1024x1024, \+ wind) " $f | cut -d'|' -f2,5,7,8; done
for f in $out/flag512-*.txt; do echo "== $f"; grep -E "GPU frame time|GPU stage" $f; done
