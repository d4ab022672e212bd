# H100, after the triangle contacts' array became a bit mask (run.sh measured the 1024 x 1024
# cloth's constraints 911 us a substep against main's 761 with the array): main's binary
# (msdsimN) against this commit's (msdsimE, with the temporary MSD_NOFUSE switch), three
# interleaved runs; edge-pair objects now run per stage by default.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
sed 's/^self_collision = true$/self_collision = true\nself_contact = "triangles_and_edges"/' presets/towel.toml > /tmp/towel_edges.toml
sim() { timeout 150 .gl/$1 simulate --preset $2 --frames 300 --quiet 2>&1 | grep -E 'GPU frame time|error'; }
for rep in 1 2 3; do
  for bin in msdsimN msdsimE; do
    tag=$bin-$rep
    echo "$tag towel: $(sim $bin presets/towel.toml)"
    timeout 200 .gl/$bin bench --frames 100 --warmup 20 --cloth-sizes 1024 --rope-sizes 256 --filter "triangle self-contact" --out "$out/bench-$tag" > "$out/bench-$tag.log" 2>&1
    grep -E "^\| (curtain|cloth 1024)" "$out/bench-$tag.log" | cut -d'|' -f2,4,5,6,8,12 | sed "s/^/$tag: /"
  done
done
echo "msdsimE towel with edges (per stage by default): $(sim msdsimE /tmp/towel_edges.toml)"
timeout 200 .gl/msdsimE bench --frames 100 --warmup 20 --cloth-sizes 1024 --rope-sizes 256 --filter "edge self-contact" --out "$out/bench-edges" > "$out/bench-edges.log" 2>&1
grep -E "^\| (curtain|cloth 1024)" "$out/bench-edges.log" | cut -d'|' -f2,4,5,6,8,12 | sed "s/^/msdsimE edges: /"
