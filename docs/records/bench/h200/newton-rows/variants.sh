# H200: where the fused iterative methods' time goes, with GLSL variants run through
# `--shaders` (each a copy of glsl/ with one change, under .gl/v_NAME/glsl): xp_reg (XPBD's
# constants from the kernel's register copy, not the buffer), xp_floor (XPBD's class passes
# with no spring visited: the passes and barriers alone), vbd_floor (VBD's colour passes with
# no particle solved); second round (ROUND=2): xp_batch (each class pass loads both slots'
# neighbours before it computes and stores either: results bit-identical), xp_nounroll (the
# class loop not unrolled). XPBD on the 63 x 32 cloth and 40 x 40, VBD on 65 x 33 (compact),
# as run.sh, two rounds. Run from the repository root.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
P=docs/records/bench/h200/newton-rows/cloth_hanging.toml
B=.gl/msdsimN
$B simulate --preset $P --frames 60 --quiet > /dev/null 2>&1
one() {  # tag, shaders option, method, resolution, size
  out=$(timeout 120 $B simulate $2 --preset $P --set "cloth.cloth.resolution=[$4]" --set "cloth.cloth.size=[$5]" --set sim.integrator=$3 --set sim.max_strain=0 --frames 330 2>&1)
  last=$(echo "$out" | grep "^frame" | tail -300 | awk '{s+=$4} END {printf "%.3f", s/NR}')
  echo "$1 $3 $4: $last ms $(echo "$out" | grep -o 'simulation (fused)' | head -1) $(echo "$out" | grep -i error | head -1)"
}
for rep in 1 2; do
  vs="main xp_reg xp_floor vbd_floor"; [ "${ROUND:-1}" = 2 ] && vs="main xp_batch xp_nounroll"
  for v in $vs; do
    sh=""; [ $v != main ] && sh="--shaders .gl/v_$v/glsl"
    one "rep $rep $v" "$sh" xpbd 63,32 6.2,3.1
    one "rep $rep $v" "$sh" xpbd 40,40 4.0,4.0
    [ "${ROUND:-1}" = 2 ] || one "rep $rep $v" "$sh" vbd 65,33 6.4,3.2
  done
done
