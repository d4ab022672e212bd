# H200: per-pass cost against the colour passes' warps (VBD, fused): 5 and 20 iterations, and the
# floor variant (no particle solved, breakdown_variants.py) at 10 and 20, on four cloth sizes; the energy
# guard off so that the floor variant runs all frames. Output: latency.txt. Run from the repository root.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
P=docs/records/bench/h200/newton-rows/cloth_hanging.toml
B=.gl/msdsimN
$B simulate --preset $P --frames 60 --quiet > /dev/null 2>&1
one() {
  out=$(timeout 120 $B simulate $2 --preset $P --set sim.max_strain=0 --set sim.max_energy_gain=0 $3 --frames 330 2>&1)
  last=$(echo "$out" | grep "^frame" | tail -300 | awk '{s+=$4} END {printf "%.3f (%d frames)", s/NR, NR}')
  echo "$1: $last ms $(echo "$out" | grep -o 'simulation (fused[^)]*)\|simulation [^ ]*' | head -1) $(echo "$out" | grep -i error | head -1)"
}
for rep in 1 2; do
  for size in 65,33:6.4,3.2 32,32:3.1,3.1 32,16:3.1,1.5 64,32:6.3,3.1; do
    r=${size%%:*}; z=${size##*:}
    res="--set cloth.cloth.resolution=[$r] --set cloth.cloth.size=[$z]"
    for it in 5 20; do one "rep $rep $r it $it" "" "$res --set sim.iterations=$it"; done
    one "rep $rep $r floor it 10" "--shaders .gl/v_floor/glsl" "$res"
    one "rep $rep $r floor it 20" "--shaders .gl/v_floor/glsl" "$res --set sim.iterations=20"
  done
done
