# H200: a cloth's edge pairs left out within 1.33 h at rest (this change) against 1.5 h (the
# GLSL before it, 1b0c0e1, through --shaders, in the same binary), three interleaved rounds;
# then the issue-26 target cases once with this build. Run from the repository root with the
# stripped binary as .gl/msdsimC and 1b0c0e1's glsl/ as .gl/glsl_main/glsl
# (docs/gpu-device.md's recipe). Bench output under $OUT.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
# (a warm-up round, not reported: a fresh machine's first runs are slow)
.gl/msdsimC bench --frames 100 --warmup 5 --cloth-sizes 50 --filter "springs only" --out /tmp/warm > /dev/null 2>&1
sed 's/^self_collision = true$/self_collision = true\nself_contact = "triangles_and_edges"/' presets/towel.toml > /tmp/towel_edges.toml
for rep in 1 2 3; do
  for v in before after; do
    sh=""; [ $v = before ] && sh="--shaders .gl/glsl_main/glsl"
    tag=$v-$rep
    echo "$tag towel with edges: $(timeout 100 .gl/msdsimC simulate --preset /tmp/towel_edges.toml --frames 300 --quiet $sh 2>&1 | grep -E 'GPU frame time|error' | tr -s ' ' | tr '\n' ' ')"
    timeout 120 .gl/msdsimC bench $sh --frames 100 --warmup 20 --cloth-sizes 50,1024 --rope-sizes 16 --filter "edge self-contact" --out "$OUT/bench-$tag" > "$OUT/bench-$tag.log" 2>&1
    grep -h 'edge self-contact' $OUT/bench-$tag/bench.csv | sed "s/^/$tag: /"
  done
done
echo "columns: bench.csv's (ms a frame)"
