# H100: contact between objects keeping two cloths' edges apart (contact.comp's CLOTH_EDGES),
# against the GLSL before it (fe0235d, through --shaders, in the same binary: with it the
# "edges" case has the grown contact cell but no edge pairs). Run from the repository root with
# the stripped binary as .gl/msdsimC and fe0235d's glsl/ as .gl/glsl_main/glsl
# (docs/gpu-device.md's recipe). Bench output under $OUT.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
# (a warm-up round, not reported: a fresh machine's first runs are slow)
.gl/msdsimC bench --frames 20 --warmup 5 --filter "8 cloths" --out /tmp/warm > /dev/null 2>&1
for rep in 1 2 3; do
  for v in before after; do
    sh=""; [ $v = before ] && sh="--shaders .gl/glsl_main/glsl"
    tag=$v-$rep
    for p in rope_on_cloth playground; do
      echo "$tag $p: $(timeout 120 .gl/msdsimC simulate --preset presets/$p.toml --frames 300 --quiet $sh 2>&1 | grep -E 'GPU frame time|error' | tr -s ' ' | tr '\n' ' ')"
    done
    timeout 200 .gl/msdsimC bench $sh --frames 200 --warmup 30 --filter "8 cloths" --out $OUT/$tag > $OUT/$tag.log 2>&1
    echo "$tag: $(grep -h '8 cloths' $OUT/$tag/bench.csv | cut -d, -f2,7-9 | tr '\n' ' ')"
  done
done
echo "columns: case, total median, p10, p90 (ms a frame)"
