# The rest-state filter in place of the one-ring exclusion (triangle self-contact; not landed,
# ACCURACY.md "Piling, measured again"): its cost. One binary (main at c282dd9, .gl/msdsim-new)
# with main's GLSL and the variant's (.gl/vR: glsl/ of the variant, made on the build machine),
# three interleaved runs. Cases: the bench's 1024 x 1024 cloth with triangle self-contact (per
# stage) and the curtain with every feature and triangles (fused), the towel preset (fused).
# Run from the repository root on the device machine: bash docs/bench/h100/rest-filter/run.sh
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
bin=.gl/msdsim-new
for run in 1 2 3; do
  for v in glsl .gl/vR; do
    tag=$(basename $v)
    $bin bench --frames 100 --warmup 20 --cloth-sizes 50,1024 --rope-sizes 256 --filter "triangle" --shaders $v --out "$out/bench-$tag-$run" > /dev/null 2>&1
    grep -E "triangle" "$out/bench-$tag-$run/bench.md" | cut -d'|' -f2,5,8,9,12 | sed "s/^/$tag $run: /"
    echo "$tag $run towel: $($bin simulate --preset presets/towel.toml --frames 300 --quiet --shaders $v 2>&1 | grep -E 'GPU frame time')"
  done
done
