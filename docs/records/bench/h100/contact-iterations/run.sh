# Contact iterations (sim.contact_iterations, passes over a cloth's triangle self-contacts a
# substep) and contact lists of 32 entries a particle instead of 16: their cost. Two binaries
# (stripped release builds of the change: .gl/msdsim-16 with 16 list entries, .gl/msdsim-new
# with 32), K = 1, 2, 4, interleaved, two runs. Cases: the bench's self-collision cases (cloth
# 50 x 50 fused and 1024 x 1024 per stage, with particle and with triangle self-contact; the
# curtain with every feature and triangles; ropes), the towel preset (fused, 300 frames).
# Run from the repository root on the device machine: bash docs/records/bench/h100/contact-iterations/run.sh
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
for run in 1 2; do
  for bin in 16 new; do
    for k in 1 2 4; do
      [ $bin = 16 ] && [ $k != 1 ] && [ $run = 2 ] && continue
      b=.gl/msdsim-$bin
      $b bench --frames 100 --warmup 20 --cloth-sizes 50,1024 --rope-sizes 4096 --filter "self" --contact-iterations $k --out "$out/bench-$bin-$k-$run" > /dev/null 2>&1
      grep -E "self" "$out/bench-$bin-$k-$run/bench.md" | cut -d'|' -f2,5,9,12 | sed "s/^/$bin K=$k run $run: /"
      echo "$bin K=$k run $run towel: $($b simulate --preset presets/towel.toml --frames 300 --quiet --set sim.contact_iterations=$k 2>&1 | grep -E 'GPU frame time')"
    done
  done
done
