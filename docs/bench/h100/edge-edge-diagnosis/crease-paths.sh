set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
b=.gl/msdsimBH
for v in glsl .gl/b50; do
  for mode in fused staged; do
    if [ $mode = staged ]; then export MSD_NOFUSE=1; else unset MSD_NOFUSE; fi
    tag=$(echo $v | tr / _)-$mode
    echo "$tag towel: $(timeout 120 $b simulate --preset presets/towel.toml --frames 300 --quiet --shaders $v 2>&1 | grep -E 'GPU frame time|error')"
    timeout 200 $b bench --frames 100 --warmup 20 --cloth-sizes 50 --rope-sizes 16 --filter "curtain 50x50, all features, triangle" --shaders $v --out "$out/bench-$tag" > "$out/bench-$tag.log" 2>&1
    grep -E "^\| curtain" "$out/bench-$tag.log" | cut -d'|' -f2,4,5,6,8 | sed "s/^/$tag: /"
  done
done
unset MSD_NOFUSE
