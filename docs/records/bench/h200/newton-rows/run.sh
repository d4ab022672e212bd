# H200: our side of issue 31's rows on Newton's cloth_hanging geometry (cloth_hanging.toml
# here), 10 substeps x 10 iterations, 300 frames after 30, `simulate`'s GPU timestamps. Runs
# each binary named on the command line (stripped, under .gl/) on the 65 x 33 cloth and on a
# 63 x 32 one (the largest near it whose iterative layout fits 48 KiB), per method, with
# particle and triangle self-contact for VBD, and symplectic Euler at 32 substeps (Newton's
# semi-implicit row). REPS (default 2) and SIZES (default both) narrow it. Run from the
# repository root. The guard is off (sim.max_strain = 0): at 10 x 10 these springs, which carry
# 214 kg from 33 pins, pass twice their rest length (VBD at frame 167 on lavapipe) and the run
# would stop there; the timings are of the run as Newton's.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
P=docs/records/bench/h200/newton-rows/cloth_hanging.toml
BINS="$*"
$1 simulate --preset $P --frames 60 --quiet > /dev/null 2>&1  # warm the GPU
for rep in $(seq 1 ${REPS:-2}); do
for bin in $BINS; do
  for size in ${SIZES:-65,33:6.4,3.2 63,32:6.2,3.1}; do
    size=$(echo $size | tr : ' ')
    set -- $size
    res="--set cloth.cloth.resolution=[$1] --set cloth.cloth.size=[$2]"
    for m in xpbd xpbd_jacobi vbd implicit vbd+particles vbd+triangles symplectic_euler; do
      extra=""
      case $m in
        vbd+particles) extra="--set cloth.cloth.self_collision=true --set cloth.cloth.self_collision_distance=0.05 --set cloth.cloth.self_contact=particles";;
        vbd+triangles) extra="--set cloth.cloth.self_collision=true --set cloth.cloth.self_collision_distance=0.05";;
        symplectic_euler) extra="--set sim.substeps=32";;
      esac
      out=$(timeout 120 $bin simulate --preset $P $res $extra --set sim.integrator=${m%%+*} --set sim.max_strain=0 --frames 330 2>&1)
      t=$(echo "$out" | grep "GPU frame time" | sed 's/GPU frame time: //')
      path=$(echo "$out" | grep -o "simulation (fused)" | head -1)
      # the mean over the last 300 frames
      last=$(echo "$out" | grep "^frame" | tail -300 | awk '{s+=$4} END {printf "%.3f", s/NR}')
      err=$(echo "$out" | grep "error" | head -1)
      echo "rep $rep $(basename $bin) ${1} $m: last-300 mean $last ms | $t | ${path:-per stage} $err"
    done
  done
done
done
