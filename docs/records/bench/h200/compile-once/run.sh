# Contact tests compiled once (7155ab7) against the shaders before (1debe93), one binary
# (.gl/msdsim, Rust unchanged) with each commit's GLSL through --shaders (.gl/g-old, .gl/g-new),
# interleaved, three runs each: the paper's curtain with every feature (particle and triangle
# self-contact, fused), the 1024 x 1024 cloth with self-collision (particles; per stage), and
# the 128 x 128 and 1024 x 1024 cloths with triangle self-contact (per stage).
# Run from the repository root on the device machine: bash docs/records/bench/h200/compile-once/run.sh
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
for run in 1 2 3; do
  for build in old new; do
    s="--shaders .gl/g-$build"
    .gl/msdsim bench $s --frames 300 --warmup 30 --filter "curtain 50x50, all features" --out "$out/curtain-$build-$run" > /dev/null
    .gl/msdsim bench $s --frames 100 --warmup 20 --cloth-sizes 128,1024 --rope-sizes 256 --filter "self-co" --out "$out/cloth-$build-$run" > /dev/null
  done
done
tar -C "$(dirname "$out")" -cf "${OUT:-/tmp/out}/runs.tar" runs
for f in $out/*/bench.md; do echo "== $f"; grep -E "^\| (curtain|cloth)" $f | cut -d'|' -f2,5,8,9,12; done
