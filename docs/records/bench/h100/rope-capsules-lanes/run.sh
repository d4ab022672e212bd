# H100: contact between objects with ropes as capsules, a rope node's search split among 64
# lanes and the cloths' and ropes' work items in two dispatches (contact.comp's `lanes_of`,
# SEGMENTS), against main before capsules (94c94d2). Run from the repository root with the
# stripped binaries as .gl/msdsimM (main) and .gl/msdsimC (this change), docs/gpu-device.md's
# recipe. Bench output under $OUT.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
for rep in 1 2 3; do
  for b in M C; do
    for p in rope_on_cloth playground; do
      echo "$b-$rep $p: $(timeout 120 .gl/msdsim$b simulate --preset presets/$p.toml --frames 300 --quiet 2>&1 | grep -E 'GPU frame time|constraints|error' | tr -s ' ' | tr '\n' ' ')"
    done
    .gl/msdsim$b bench --frames 200 --warmup 30 --filter "8 cloths" --out $OUT/$b-$rep > $OUT/$b-$rep.log 2>&1
    echo "$b-$rep: $(grep -h '8 cloths' $OUT/$b-$rep/bench.csv | cut -d, -f2,7-9 | tr '\n' ' ')"
  done
done
echo "columns: case, total median, p10, p90 (ms a frame)"
