# Triangle self-contact with friction and the velocity/position split (69a8da5, .gl/msdsim)
# against the build before (1493d40, .gl/msdsim-old), interleaved, three runs each: the paper's
# curtain with every feature and triangle self-contact (fused) and the 128 x 128 and
# 1024 x 1024 cloths with triangle self-contact (per stage). Run from the repository root on
# the device machine: bash docs/bench/h100/self-contact-friction/run.sh
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
for run in 1 2 3; do
  for build in old new; do
    bin=.gl/msdsim-$build; [ $build = new ] && bin=.gl/msdsim
    $bin bench --frames 300 --warmup 30 --filter "curtain 50x50, all features, triangle" --out "$out/curtain-$build-$run" > /dev/null
    $bin bench --frames 100 --warmup 20 --cloth-sizes 128,1024 --rope-sizes 256 --filter "+ triangle self-contact" --out "$out/cloth-$build-$run" > /dev/null
  done
done
tar -C "$(dirname "$out")" -cf "${OUT:-/tmp/out}/runs.tar" runs
for f in $out/*/bench.md; do echo "== $f"; grep -E "triangle" $f | cut -d'|' -f2,5,8,9,12; done
