# H100: edge contact's ring creases computed once where the hash is built (this commit) against
# computed for every candidate (the GLSL before it, through --shaders, in the same binary).
# Run from the repository root with the stripped binary as .gl/msdsimC and the previous
# commit's glsl/ as .gl/glsl_main/glsl (docs/gpu-device.md's recipe).
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
sed 's/^self_collision = true$/self_collision = true\nself_contact = "triangles_and_edges"/' presets/towel.toml > /tmp/towel_edges.toml
grep -c triangles_and_edges /tmp/towel_edges.toml
for rep in 1 2 3; do
  for v in before after; do
    sh=""; [ $v = before ] && sh="--shaders .gl/glsl_main/glsl"
    tag=$v-$rep
    echo "$tag towel with edges: $(timeout 150 .gl/msdsimC simulate --preset /tmp/towel_edges.toml --frames 300 --quiet $sh 2>&1 | grep -E 'GPU frame time|error')"
    timeout 250 .gl/msdsimC bench $sh --frames 100 --warmup 20 --cloth-sizes 50,1024 --rope-sizes 16 --filter "triangle" --out "$out/bench-$tag" > "$out/bench-$tag.log" 2>&1
    grep -E "^\| (curtain|cloth)" "$out/bench-$tag.log" | cut -d'|' -f2,4,5,6,8,12 | sed "s/^/$tag: /"
  done
done
