set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
bin=.gl/msdsimH
for rep in 1 2; do
for v in .gl/old/glsl .gl/olds/glsl .gl/v32 .gl/v32s; do
  tag=$(echo $v | tr "/" "_")
  echo "$rep $tag towel fused: $($bin simulate --preset presets/towel.toml --frames 200 --quiet --shaders $v 2>&1 | grep -E 'GPU frame time|GPU stage|error' | tr '\n' ' ')"
  echo "$rep $tag towel staged: $(MSD_NOFUSE=1 $bin simulate --preset presets/towel.toml --frames 200 --quiet --shaders $v 2>&1 | grep -E 'GPU frame time|GPU stage|error' | tr '\n' ' ')"
  if [ $rep = 1 ]; then
  $bin bench --frames 100 --warmup 20 --cloth-sizes 1024 --rope-sizes 256 --filter "triangle" --shaders $v --out "$out/bench-$tag" > "$out/bench-$tag.log" 2>&1
  grep -E "triangle" "$out/bench-$tag/bench.md" | cut -d'|' -f2,4,5,12- | sed "s/^/$tag: /"
  fi
done
done
