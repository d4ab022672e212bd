# The contact lists' skin for triangle self-contact (TRIANGLE_LIST_SKIN, glsl/include/lists.glsl), H100.
# Step 1 (variants.txt): one binary (.gl/msdsimM, `cargo build --release` of main at 484b9b3, stripped), GLSL through
# --shaders: main's (.gl/old/glsl, skin 1) and copies with the triangle skin at 0.25, 0.5, 0.75 (.gl/m25, m50, m75).
# Step 2 (this script, results.txt): main's binary against the change's (.gl/msdsimN), built-in GLSL, three
# interleaved runs. Run from the repository root on the device machine: bash docs/records/bench/h100/list-skin-triangles/run.sh
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
for rep in 1 2 3; do
  for bin in msdsimM msdsimN; do
    tag=$bin-$rep
    .gl/$bin bench --frames 100 --warmup 20 --cloth-sizes 1024 --rope-sizes 256 --filter "triangle" --out "$out/bench-$tag" > "$out/bench-$tag.log" 2>&1
    grep -E "^\| (curtain|cloth 1024|rope)" "$out/bench-$tag.log" | cut -d'|' -f2,5,6,8,12 | sed "s/^/$tag: /"
    for p in towel tablecloth; do
      echo "$tag $p: $(.gl/$bin simulate --preset presets/$p.toml --frames 300 --quiet 2>&1 | grep -E 'GPU frame time|error')"
    done
  done
done
