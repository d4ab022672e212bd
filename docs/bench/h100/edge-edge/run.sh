# Edge-edge self-contact's cost (issue 26; branch edge-edge-gpu, 63ac42f, not on main): one
# binary (.gl/msdsim, `cargo build --release` of the branch, stripped) with main's GLSL before it
# (.gl/old/glsl: `git archive fdcce3a glsl | tar -x -C .gl/old`) and the branch's own (glsl, the
# branch checked out), interleaved, two runs each: the 1024 x 1024 cloth with triangle
# self-contact (per stage; bench case "+ triangle self-contact"), the curtain with every feature
# and triangle self-contact (fused), and the towel preset, 300 frames (fused, triangles).
# Run from the repository root on the device machine: bash docs/bench/h100/edge-edge/run.sh
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
bin=.gl/msdsim
for run in 1 2; do
  for v in .gl/old/glsl glsl; do
    tag=$( [ "$v" = glsl ] && echo new || echo old )
    $bin bench --frames 100 --warmup 20 --cloth-sizes 1024 --rope-sizes 256 --filter "triangle" --shaders $v --out "$out/bench-$tag-$run" > "$out/bench-$tag-$run.log" 2>&1
    grep -E "triangle" "$out/bench-$tag-$run/bench.md" | sed "s/^/$tag $run: /"
    echo "$tag $run towel: $($bin simulate --preset presets/towel.toml --frames 300 --quiet --shaders $v 2>&1 | grep -E 'GPU frame time|error')"
  done
done
