# H100: the fused kernel's contact lists rebuilt when the box around every particle's move since
# their build outgrows the skin (this commit's GLSL, copied to .gl/vL/glsl) against main's
# (msdsimE's own shaders: main at 59b0a07 plus a host-side switch not used here), one binary,
# three interleaved runs; run from the repository root with msdsimE in .gl/.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
for rep in 1 2 3; do
  for v in main .gl/vL/glsl; do
    sh=""; [ $v = main ] || sh="--shaders $v"
    tag=$(echo $v | tr / _)-$rep
    echo "$tag towel: $(timeout 150 .gl/msdsimE simulate --preset presets/towel.toml --frames 300 --quiet $sh 2>&1 | grep -E 'GPU frame time|error')"
    echo "$tag tablecloth: $(timeout 150 .gl/msdsimE simulate --preset presets/tablecloth.toml --frames 300 --quiet $sh 2>&1 | grep -E 'GPU frame time|error')"
    timeout 100 .gl/msdsimE bench --frames 200 --warmup 30 --cloth-sizes 50 --rope-sizes 256 --filter "all features" $sh --out "$out/bench-$tag" > "$out/bench-$tag.log" 2>&1
    grep -E "^\| (curtain|rope|cloth)" "$out/bench-$tag.log" | grep -v "edge self" | cut -d'|' -f2,4,5,6,8 | sed "s/^/$tag: /"
  done
done
