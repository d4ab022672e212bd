# H200: where VBD's fused frame on Newton's 65 x 33 cloth (compact layout) goes, with GLSL
# variants through `--shaders` (each a copy of glsl/ with one change, under .gl/v_NAME/glsl,
# made by breakdown_variants.py): nohess (each spring adds to the force only, the Hessian
# bounded by (m / h^2 + sum (k + b / h)) I: the cost a per-vertex XPBD visit would have, no
# 3x3 block), nodamp (no dashpots: no neighbour displacement read), eight (the structural
# and shear springs only, not the bending ones), floor (no particle solved). Also main at 5
# and 20 iterations (the cost of an iteration's five colour passes against the substep's
# rest). Two rounds, as run.sh (mean of the last 300 of 330 frames; a variant that stops on
# the energy guard gives the mean of the frames it ran). ROUND=2 runs the second round's
# variants (below). Run from the repository root.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
P=docs/records/bench/h200/newton-rows/cloth_hanging.toml
B=.gl/msdsimN
$B simulate --preset $P --frames 60 --quiet > /dev/null 2>&1
one() {  # tag, shaders option, extra settings
  out=$(timeout 120 $B simulate $2 --preset $P --set sim.max_strain=0 $3 --frames 330 2>&1)
  last=$(echo "$out" | grep "^frame" | tail -300 | awk '{s+=$4} END {printf "%.3f (%d frames)", s/NR, NR}')
  echo "$1: $last ms $(echo "$out" | grep -o 'simulation (fused[^)]*)' | head -1) $(echo "$out" | grep -i error | head -1)"
}
if [ "${ROUND:-1}" = 2 ]; then
  # Second round: bare (nohess and nodamp together), and VBD with triangle self-contact
  # (Newton's default) against notest and nosearch.
  tri="--set cloth.cloth.self_collision=true --set cloth.cloth.self_collision_distance=0.05"
  for rep in 1 2; do
    for v in main bare; do
      sh=""; [ $v != main ] && sh="--shaders .gl/v_$v/glsl"
      one "rep $rep $v vbd 65,33" "$sh" ""
    done
    for v in main notest nosearch; do
      sh=""; [ $v != main ] && sh="--shaders .gl/v_$v/glsl"
      one "rep $rep $v vbd+triangles 65,33" "$sh" "$tri"
    done
  done
  exit 0
fi
for rep in 1 2; do
  for v in main nohess nodamp eight floor; do
    sh=""; [ $v != main ] && sh="--shaders .gl/v_$v/glsl"
    one "rep $rep $v vbd 65,33" "$sh" ""
  done
  for it in 5 20; do one "rep $rep main vbd 65,33 iterations $it" "" "--set sim.iterations=$it"; done
  one "rep $rep main vbd 32,32" "" "--set cloth.cloth.resolution=[32,32] --set cloth.cloth.size=[3.1,3.1]"
  one "rep $rep nohess vbd 32,32" "--shaders .gl/v_nohess/glsl" "--set cloth.cloth.resolution=[32,32] --set cloth.cloth.size=[3.1,3.1]"
done
