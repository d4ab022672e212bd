# msdsimE (run2.sh) with three shader trees: this commit's (glsl), main's (.gl/vA/glsl: git archive
# main glsl | tar -x -C .gl/vA) and this commit's with, in self_triangles_of, "if (!edge_contact())
# test_contact(t, uvec4(pair_particle, tv), d, 1.0); else" before the hits bit (.gl/vC/glsl).
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
for rep in 1 2; do
  for v in glsl .gl/vA/glsl .gl/vC/glsl; do
    tag=$(echo $v | tr / _)-$rep
    timeout 200 .gl/msdsimE bench --frames 100 --warmup 20 --cloth-sizes 1024 --rope-sizes 256 --filter "cloth 1024x1024, + triangle self-contact" --shaders $v --out "$out/bench-$tag" > "$out/bench-$tag.log" 2>&1
    grep -E "^\| (curtain|cloth 1024)" "$out/bench-$tag.log" | cut -d'|' -f2,4,5,6,8,12 | sed "s/^/$tag: /"
  done
done
