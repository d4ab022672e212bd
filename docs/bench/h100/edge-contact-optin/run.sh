# H100: main's binary (msdsimN, 4a95070) against the opt-in edge contact's (msdsimE: this
# commit's tree plus a temporary MSD_NOFUSE switch that runs every object per stage), run from
# the repository root with both binaries in .gl/ (docs/gpu-device.md's recipe).
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
sed 's/^self_collision = true$/self_collision = true\nself_contact = "triangles_and_edges"/' presets/towel.toml > /tmp/towel_edges.toml
grep -c triangles_and_edges /tmp/towel_edges.toml
sim() { timeout 150 .gl/$1 simulate --preset $2 --frames 300 --quiet 2>&1 | grep -E 'GPU frame time|error'; }
for rep in 1 2; do
  for bin in msdsimN msdsimE; do
    tag=$bin-$rep
    echo "$tag towel: $(sim $bin presets/towel.toml)"
    timeout 200 .gl/$bin bench --frames 100 --warmup 20 --cloth-sizes 1024 --rope-sizes 256 --filter "triangle" --out "$out/bench-$tag" > "$out/bench-$tag.log" 2>&1
    grep -E "^\| (curtain|cloth 1024)" "$out/bench-$tag.log" | cut -d'|' -f2,4,5,6,8,12 | sed "s/^/$tag: /"
  done
  echo "msdsimE-$rep towel with edges, fused: $(sim msdsimE /tmp/towel_edges.toml)"
  echo "msdsimE-$rep towel with edges, per stage: $(MSD_NOFUSE=1 sim msdsimE /tmp/towel_edges.toml)"
  timeout 200 .gl/msdsimE bench --per-stage --frames 100 --warmup 20 --cloth-sizes 50 --rope-sizes 16 --filter "curtain 50x50, all features, triangle" --out "$out/bench-staged-$rep" > "$out/bench-staged-$rep.log" 2>&1
  grep -E "^\| curtain" "$out/bench-staged-$rep.log" | cut -d'|' -f2,4,5,6,8,12 | sed "s/^/msdsimE-$rep per stage: /"
done
