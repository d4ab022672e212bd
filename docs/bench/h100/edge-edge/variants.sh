# Where the branch's towel time goes (one run each, 300 frames; the bench lines of this call failed and are not
# reported): .gl/vA the branch's GLSL with self_edges never called (the restructure alone); .gl/vB edge pairs but
# the one-ring left out of the search again (rest_neighbour as on main); .gl/vC edge pairs never written to the contact
# lists (wrong: listed substeps miss them; for the cost only). Made from the branch's glsl (cp -r glsl .gl/vX), one edit each:
#   vA include/self_contact.glsl: `if (j > pair_particle) self_edges(` -> `if (false && j > pair_particle) self_edges(`
#   vB include/constraints_body.glsl, rest_neighbour: `if (triangle_contact()) return j == cell.x + cell.y * obj.dims.x;`
#      -> return whether j is in the particle's one-ring (grid offsets at most 1)
#   vC include/self_contact.glsl, self_edges: `if (d < list_reach) {` -> `if (false && d < list_reach) {`
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
bin=.gl/msdsim
for v in .gl/old/glsl glsl .gl/vA .gl/vB .gl/vC; do
  tag=$(echo $v | tr '/' '_')
  $bin bench --frames 60 --warmup 10 --cloth-sizes 1024 --rope-sizes 256 --filter "triangle" --shaders $v --out "$out/b$tag" > /dev/null 2>&1
  grep -E "curtain|cloth 1024" "$out/b$tag/bench.md" | cut -d'|' -f2,5,12 | sed "s/^/$tag: /"
  echo "$tag towel: $($bin simulate --preset presets/towel.toml --frames 300 --quiet --shaders $v 2>&1 | grep -E 'GPU frame time|error')"
done
