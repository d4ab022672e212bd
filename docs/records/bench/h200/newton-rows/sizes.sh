# H200: the iterative methods on square cloths of 1,600 and 2,025 particles (cloth_hanging.toml
# resized, 10 substeps x 10 iterations, 300 frames after 30) with each binary named on the
# command line: main's runs them per stage (more than 1,024 particles), the branch's fused with
# two particles a thread. Run from the repository root.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
P=docs/records/bench/h200/newton-rows/cloth_hanging.toml
for rep in 1 2; do
for bin in "$@"; do
  for size in 40 45; do
    for m in xpbd xpbd_jacobi vbd implicit; do
      out=$(timeout 120 $bin simulate --preset $P --set "cloth.cloth.resolution=[$size,$size]" --set "cloth.cloth.size=[4.0,4.0]" --set sim.integrator=$m --frames 330 2>&1)
      path=$(echo "$out" | grep -o "simulation (fused)" | head -1)
      last=$(echo "$out" | grep "^frame" | tail -300 | awk '{s+=$4} END {printf "%.3f", s/NR}')
      echo "rep $rep $(basename $bin) ${size}x$size $m: last-300 mean $last ms | ${path:-per stage}"
    done
  done
done
done
