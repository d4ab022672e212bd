# 3831a03's hot-path change (one triangle_distance for every search, the box cull's 0.1%
# margin) against d0680df's GLSL (in .gl/base/glsl through --shaders: git archive d0680df glsl),
# one binary (.gl/msdsim, at 8d8d884), interleaved, three runs each.
# Run from the repository root on the device machine: bash docs/bench/h100/triangle-cost/run-shared.sh
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
bin=.gl/msdsim
for run in 1 2 3; do
  for v in base new; do
    sh=""; [ $v = base ] && sh="--shaders .gl/base/glsl"
    $bin bench --frames 100 --warmup 20 --cloth-sizes 1024 --rope-sizes 256 --filter "triangle" $sh --out "$out/$v-$run" > /dev/null 2>&1
    grep -E "triangle" "$out/$v-$run/bench.md" | cut -d"|" -f2,5,6,9,12 | sed "s/^/$v $run: /"
    echo "$v $run towel: $($bin simulate --preset presets/towel.toml --frames 300 --quiet $sh 2>&1 | grep -E 'GPU frame time')"
  done
done
