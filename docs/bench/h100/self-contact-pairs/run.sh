# Self-contact against triangles: the build that has it (.gl/msdsim) against the one before
# (d0aee6a, .gl/msdsim-old), interleaved, three runs each: the paper's curtain with every feature
# (fused; with particle contact, and with `self_contact = "triangles"` on the new build) and the
# 1024 x 1024 cloth with self-collision (per stage; likewise). Run from the repository root on
# the device machine: bash docs/bench/h100/self-contact-pairs/run.sh
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
for run in 1 2 3; do
  for build in old new; do
    bin=.gl/msdsim-$build; [ $build = new ] && bin=.gl/msdsim
    $bin bench --frames 300 --warmup 30 --filter "curtain 50x50, all features" --out "$out/curtain-$build-$run" > /dev/null
    $bin bench --frames 100 --warmup 20 --cloth-sizes 1024 --rope-sizes 256 --filter "1024x1024, + " --out "$out/cloth1024-$build-$run" > /dev/null
  done
done
tar -C "$(dirname "$out")" -cf "${OUT:-/tmp/out}/runs.tar" runs
for f in $out/*/bench.md; do echo "== $f"; grep -E "self-collision \||self-contact \||all features[^+]*\|" $f | cut -d'|' -f2,5,8,9,12; done
