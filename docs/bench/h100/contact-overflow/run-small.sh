# The same variants on scenes that rarely pass PAIR_MAX: the bench's curtain with triangle
# self-contact (fused) and the towel preset (fused), interleaved, three runs.
# Run from the repository root on the device machine: bash docs/bench/h100/contact-overflow/run-small.sh
set -u
[ $# -gt 0 ] || set -- base=.gl/base/glsl v4=.gl/v4
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/small; mkdir -p "$out"
bin=.gl/msdsim
for run in 1 2 3; do
  for variant in "$@"; do
    v=${variant%%=*}; dir=${variant#*=}
    sh=""; [ -n "$dir" ] && sh="--shaders $dir"
    $bin bench --frames 100 --warmup 20 --cloth-sizes 50,128 --rope-sizes 256 --filter "triangle" $sh --out "$out/$v-$run" > /dev/null 2>&1
    grep -E "cloth|curtain" "$out/$v-$run/bench.md" | grep triangle | cut -d"|" -f2,4,5,6,9,12 | sed "s/^/$v $run: /"
    echo "$v $run towel: $($bin simulate --preset presets/towel.toml --frames 300 --quiet $sh 2>&1 | grep -E 'GPU frame time')"
  done
done
