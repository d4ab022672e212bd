# H200: more particles a thread, fewer threads (more registers each) for the fused iterative
# methods. .gl/msdsimX is a build of 9f22662 whose FusedShape::plan takes at least
# MSDSIM_EXP_SLOTS particles a thread (one line, not kept). Two rounds. From the repository root.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
P=docs/records/bench/h200/newton-rows/cloth_hanging.toml
B=.gl/msdsimX
$B simulate --preset $P --frames 60 --quiet > /dev/null 2>&1
one() {  # tag, method, resolution, size
  out=$(timeout 120 $B simulate --preset $P --set "cloth.cloth.resolution=[$3]" --set "cloth.cloth.size=[$4]" --set sim.integrator=$2 --set sim.max_strain=0 --frames 330 2>&1)
  last=$(echo "$out" | grep "^frame" | tail -300 | awk '{s+=$4} END {printf "%.3f", s/NR}')
  echo "$1 $2 $3: $last ms $(echo "$out" | grep -o 'simulation (fused)' | head -1) $(echo "$out" | grep -i error | head -1)"
}
for rep in 1 2; do
  for s in 1 2 3 4; do
    export MSDSIM_EXP_SLOTS=$s
    one "rep $rep slots>=$s" xpbd 63,32 6.2,3.1
    one "rep $rep slots>=$s" xpbd 32,32 3.2,3.2
    one "rep $rep slots>=$s" vbd 65,33 6.4,3.2
    one "rep $rep slots>=$s" vbd 32,32 3.2,3.2
    one "rep $rep slots>=$s" implicit 40,40 4.0,4.0
  done
done
