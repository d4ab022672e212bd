# H100: the crease gate at a sag of 0.1-0.2 h (this tree), 0.2-0.3 (.gl/c2/glsl: CREASE_FROM 0.2,
# CREASE_TO 0.3, CREASE_LIST 0.15) and 0.3-0.4 (.gl/c3/glsl: 0.3, 0.4, 0.25) through --shaders, msdsimE
# of run2.sh, two interleaved runs.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
sed 's/^self_collision = true$/self_collision = true\nself_contact = "triangles_and_edges"/' presets/towel.toml > /tmp/towel_edges.toml
for rep in 1 2; do
  for v in glsl .gl/c2/glsl .gl/c3/glsl; do
    tag=$(echo $v | tr / _)-$rep
    echo "$tag towel edges: $(timeout 100 .gl/msdsimE simulate --preset /tmp/towel_edges.toml --frames 300 --quiet --shaders $v 2>&1 | grep -E 'GPU frame time|error')"
    timeout 100 .gl/msdsimE bench --frames 100 --warmup 20 --cloth-sizes 1024 --rope-sizes 256 --filter "edge self-contact" --shaders $v --out "$out/bench-$tag" > "$out/bench-$tag.log" 2>&1
    grep -E "^\| (curtain|cloth 1024)|rror" "$out/bench-$tag.log" | cut -d'|' -f2,4,5,6,8,12 | sed "s/^/$tag: /"
  done
done
