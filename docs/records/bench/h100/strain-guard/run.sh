# The plausibility guard's cost (6612830, .gl/msdsim-guard) against the build before it
# (b244841, .gl/msdsim), interleaved, three runs each: the guard reads each particle's
# structural neighbours once a frame in the surface stage. Run from the repository root on the
# device machine: bash docs/records/bench/h100/strain-guard/run.sh
# Result: the curtain with the check on costs what it did (runs/curtain-*: 0.383, 0.359, 0.359
# against 0.366, 0.358, 0.358 ms a frame; surface stage 0.006 against 0.005 ms). The guard build's
# springs-only runs wrote nothing: the guard stopped the bench's 1024 x 1024 cloth, which hangs
# far past twice its rest length, so bench now runs with the check off (371365d).
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
for run in 1 2 3; do
  for build in before guard; do
    bin=.gl/msdsim-$build; [ $build = before ] && bin=.gl/msdsim
    $bin bench --frames 300 --warmup 30 --filter "curtain 50x50, all features" --out "$out/curtain-$build-$run" > /dev/null
    $bin bench --frames 100 --warmup 20 --cloth-sizes 1024 --rope-sizes 65536 --filter "springs only" --out "$out/springs-$build-$run" > /dev/null
  done
done
tar -C "$(dirname "$out")" -cf "${OUT:-/tmp/out}/runs.tar" runs
for f in $out/*/bench.md; do echo "== $f"; grep -E "^\| (cloth|rope|curtain)" $f | cut -d'|' -f2,5,10; done
