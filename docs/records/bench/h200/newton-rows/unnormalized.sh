# H200: newton_particle's spring loop in delta rather than n (the unnormalized form), and the
# compact layout's dashpots in displacements over h (SD_PER_H), against main, as GLSL variants
# through --shaders on one binary (the branch's, .gl/msdsimE): v_main = main's glsl/, v_new =
# both (the branch's glsl/), v_un = the unnormalized loop alone, v_u = the dashpots over h alone,
# v_hp = v_new with the implicit method's Hessian product unnormalized too. Newton's cloth
# settings (cloth_hanging.toml), 10 x 10, mean of the last 300 of 330 frames, two rounds.
# Run from the repository root; output in unnormalized.txt. VARIANTS overrides the list (the
# second call: main, un = v_hp as kept, sel = un with the other end's index a spring with none
# reads being the particle itself, taken from the mask with one select, and a spring on when
# its ends are apart: `on = dd > 0`).
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
P=docs/records/bench/h200/newton-rows/cloth_hanging.toml
B=.gl/msdsimE
$B simulate --preset $P --frames 60 --quiet > /dev/null 2>&1
one() {
  out=$(timeout 120 $B simulate --shaders .gl/v_$2/glsl --preset $P --set sim.max_strain=0 $3 --frames 330 2>&1)
  last=$(echo "$out" | grep "^frame" | tail -300 | awk '{s+=$4} END {printf "%.3f (%d frames)", s/NR, NR}')
  echo "$1 $2: $last ms $(echo "$out" | grep -o 'simulation (fused[^)]*)' | head -1) $(echo "$out" | grep -i error | head -1)"
}
for rep in 1 2; do
  for v in ${VARIANTS:-main new un u hp}; do
    one "rep $rep vbd 65,33" $v ""
    one "rep $rep vbd 65,33 no dashpots" $v "--set cloth.cloth.damping=0"
    one "rep $rep vbd+particles 65,33" $v "--set cloth.cloth.self_collision=true --set cloth.cloth.self_collision_distance=0.05 --set cloth.cloth.self_contact=particles"
    one "rep $rep vbd 64,32" $v "--set cloth.cloth.resolution=[64,32] --set cloth.cloth.size=[6.3,3.1]"
    one "rep $rep vbd 65,64 (per stage)" $v "--set cloth.cloth.resolution=[65,64] --set cloth.cloth.size=[6.4,6.3]"
    one "rep $rep implicit 40,40" $v "--set sim.integrator=implicit --set cloth.cloth.resolution=[40,40] --set cloth.cloth.size=[3.9,3.9]"
    one "rep $rep implicit 65,33 (per stage)" $v "--set sim.integrator=implicit"
  done
done
