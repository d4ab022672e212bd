# H200: the colour pass's one-word test (a pinned or empty slot has no colour) and VBD's
# 3x3 solve by the adjugate's product scaled once (the v_x variant of unnormalized.sh's third
# call, against v_cur = 45a1180's glsl/), then the same built into the binary (.gl/msdsimF):
# VBD on Newton's cloth (cloth_hanging.toml), 10 x 10, mean of the last 300 of 330 frames.
# Run from the repository root; output in colour_test.txt.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
P=docs/records/bench/h200/newton-rows/cloth_hanging.toml
B=.gl/msdsimF
$B simulate --preset $P --frames 60 --quiet > /dev/null 2>&1
for rep in 1 2; do
  for extra in "" "--set cloth.cloth.damping=0" "--set cloth.cloth.self_collision=true --set cloth.cloth.self_collision_distance=0.05 --set cloth.cloth.self_contact=particles"; do
    out=$(timeout 120 $B simulate --preset $P --set sim.max_strain=0 $extra --frames 330 2>&1)
    last=$(echo "$out" | grep "^frame" | tail -300 | awk '{s+=$4} END {printf "%.3f (%d frames)", s/NR, NR}')
    echo "rep $rep msdsimF vbd 65,33 $extra: $last ms $(echo "$out" | grep -o 'simulation (fused[^)]*)' | head -1)"
  done
done
