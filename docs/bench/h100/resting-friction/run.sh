# H100: self-contact friction at the contact's weight over its particles' counts (beb9684)
# against the GLSL before it (f710435, through --shaders, in the same binary).
# Run from the repository root with the stripped binary as .gl/msdsimC and f710435's glsl/ as
# .gl/glsl_main/glsl (docs/gpu-device.md's recipe).
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
# (a warm-up round, not reported: a fresh machine's first runs are slow)
.gl/msdsimC bench --frames 20 --warmup 5 --cloth-sizes 50 --rope-sizes 16 --filter "triangle" > /dev/null 2>&1
for rep in 1 2 3; do
  for v in before after; do
    sh=""; [ $v = before ] && sh="--shaders .gl/glsl_main/glsl"
    tag=$v-$rep
    echo "$tag towel: $(timeout 150 .gl/msdsimC simulate --preset presets/towel.toml --frames 300 --quiet $sh 2>&1 | grep -E 'GPU frame time|error')"
    timeout 200 .gl/msdsimC bench $sh --frames 100 --warmup 20 --cloth-sizes 50,1024 --rope-sizes 256 --filter "triangle" --out "$out/bench-$tag" > "$out/bench-$tag.log" 2>&1
    grep -E "^\| (curtain|cloth)" "$out/bench-$tag.log" | cut -d'|' -f2,4,5,6,8,12 | sed "s/^/$tag: /"
    timeout 100 .gl/msdsimC bench $sh --frames 200 --warmup 30 --cloth-sizes 16 --rope-sizes 256 --filter "rope 256, + self" --out "$out/rope-$tag" > "$out/rope-$tag.log" 2>&1
    grep -E "^\| rope" "$out/rope-$tag.log" | cut -d'|' -f2,4,5,6,8,12 | sed "s/^/$tag: /"
  done
done
