# Step 1 of the triangle skin study: main binary, GLSL variants made by skinpatch.py (python3 skinpatch.py DIR 0.5 on a
# copy of main's glsl/), two interleaved runs. Run from the repository root on the device machine.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
bin=.gl/msdsimM
for rep in 1 2; do
for v in .gl/old/glsl .gl/m25 .gl/m50 .gl/m75; do
  tag=$(echo $v | tr "/" "_")$rep
  $bin bench --frames 100 --warmup 20 --cloth-sizes 1024 --rope-sizes 256 --filter "triangle" --shaders $v --out "$out/bench-$tag" > "$out/bench-$tag.log" 2>&1
  grep -E "curtain|cloth 1024" "$out/bench-$tag/bench.md" | cut -d'|' -f2,5,12- | sed "s/^/$tag: /"
  for p in towel tablecloth; do
  echo "$tag $p: $($bin simulate --preset presets/$p.toml --frames 300 --quiet --shaders $v 2>&1 | grep -E 'GPU frame time|error' | tr '\n' ' ')"
  done
done
done
