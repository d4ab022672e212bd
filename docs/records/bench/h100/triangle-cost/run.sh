# Where triangle self-contact's time goes: the same binary (.gl/msdsim) with its own GLSL and
# two variants through --shaders: vA skips the triangle tests (the hash scan alone), vB skips the
# search (the passes alone). Cases: the 1024 x 1024 cloth with triangle self-contact (per stage)
# and with particle contact, the towel preset with triangles (fused, 300 frames) and particles.
# Run from the repository root on the device machine: bash docs/records/bench/h100/triangle-cost/run.sh
set -u
# The variants, made on the build machine before the call (.gl travels with it):
#   cp -r glsl .gl/vA; sed -i 's/^void self_triangles(uvec2 cell, vec3 x, uint j, float list_reach) {$/&\n    if (obj.self_distance > 0.0) return;/' .gl/vA/include/self_contact.glsl
#   cp -r glsl .gl/vB; sed -i 's/^            self_search(cell, x, unused, unused_count);$/            if (obj.self_distance < 0.0) self_search(cell, x, unused, unused_count);/' .gl/vB/include/constraints_body.glsl
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
bin=.gl/msdsim
for run in 1 2; do
  for v in glsl .gl/vA .gl/vB; do
    tag=$(basename $v)
    $bin bench --frames 100 --warmup 20 --cloth-sizes 1024 --rope-sizes 256 --filter "self-co" --shaders $v --out "$out/cloth-$tag-$run" > /dev/null 2>&1
    grep -E "self-co" "$out/cloth-$tag-$run/bench.md" | cut -d'|' -f2,5,8,9,12 | sed "s/^/$tag $run: /"
    for m in triangles particles; do
      echo "$tag $run towel $m: $($bin simulate --preset presets/towel.toml --frames 300 --quiet --shaders $v --set "cloth.0.self_contact=\"$m\"" 2>&1 | grep -E 'GPU frame time')"
    done
  done
done
