# H200: the branch-free spring loops (SELECT_SPRINGS in the fused kernel) against the branches,
# VBD and the implicit method on Newton's cloth settings (cloth_hanging.toml), fused and per
# stage. Run from the repository root with the stripped binary of 2baaa32 as .gl/msdsimN (main,
# its built-in GLSL) and .gl/v_fin/glsl a copy of this commit's glsl/ (fin); .gl/v_bf6/glsl is fin
# with the selects in the per-stage shaders too. Two rounds; output in branchfree.txt, with the
# runs of the variants tried and not kept (branchfree-variants.patch: bf4, one, sf against fin).
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
P=docs/records/bench/h200/newton-rows/cloth_hanging.toml
B=.gl/msdsimN
$B simulate --preset $P --frames 60 --quiet > /dev/null 2>&1
one() {
  out=$(timeout 120 $B simulate $2 --preset $P --set sim.max_strain=0 $3 --frames 330 2>&1)
  last=$(echo "$out" | grep "^frame" | tail -300 | awk '{s+=$4} END {printf "%.3f (%d frames)", s/NR, NR}')
  echo "$1: $last ms $(echo "$out" | grep -o 'simulation (fused[^)]*)\|simulation [^ ]*\|physics + fused' | head -1) $(echo "$out" | grep -i error | head -1)"
}
for rep in 1 2; do
  for size in 65,33:6.4,3.2 32,16:3.1,1.5 32,32:3.1,3.1 64,32:6.3,3.1 65,64:6.4,6.3; do
    r=${size%%:*}; z=${size##*:}
    res="--set cloth.cloth.resolution=[$r] --set cloth.cloth.size=[$z]"
    for v in main bf6 fin; do
      sh=""; [ $v != main ] && sh="--shaders .gl/v_$v/glsl"
      one "rep $rep $v vbd $r" "$sh" "$res"
    done
  done
  for v in main bf6 fin; do
    sh=""; [ $v != main ] && sh="--shaders .gl/v_$v/glsl"
    one "rep $rep $v vbd 65,33 no dashpots" "$sh" "--set cloth.cloth.damping=0"
    one "rep $rep $v vbd+particles 65,33" "$sh" "--set cloth.cloth.self_collision=true --set cloth.cloth.self_collision_distance=0.05 --set cloth.cloth.self_contact=particles"
    one "rep $rep $v vbd+triangles 65,33" "$sh" "--set cloth.cloth.self_collision=true --set cloth.cloth.self_collision_distance=0.05"
    one "rep $rep $v implicit 40,40" "$sh" "--set sim.integrator=implicit --set cloth.cloth.resolution=[40,40] --set cloth.cloth.size=[3.9,3.9]"
    one "rep $rep $v implicit 65,33" "$sh" "--set sim.integrator=implicit"
  done
done
