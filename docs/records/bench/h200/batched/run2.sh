#!/bin/bash
# A chunk of objects a dispatch in the per-stage passes (msdsim_new, 5d1c260) against one
# dispatch an object (msdsim_base, main 3bc50b6), A/B in one lease on the H200, two rounds; then
# the same frames from both builds, and the contact lists' skin (an experiment build).
for f in .gl/*.deb; do dpkg -x $f / ; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
full=""; for k in 0 1 2 3 4 5 6 7; do
  full="$full --set cloth.$k.self_collision=true --set cloth.$k.self_contact=triangles_and_edges"; done
run() { B=$1; shift; echo "== $B $*" | cut -c1-110; .gl/$B simulate "$@" --quiet 2>&1 | grep -E "GPU frame|GPU stage|error" ; }
for round in 1 2; do
  for B in msdsim_base msdsim_new; do
    run $B --preset .gl/poker52.toml --frames 120
    run $B --preset .gl/stack8.toml --frames 230
    run $B --preset .gl/stack8.toml --frames 230 $full
    run $B --preset .gl/stack8.toml --frames 230 --set sim.integrator=xpbd
  done
done
for B in msdsim_base msdsim_new; do
  .gl/$B bench --filter "8 cloths" --out $OUT/bench-$B 2>&1 | grep "^| 8"
done
for P in .gl/poker52.toml .gl/stack8.toml presets/rope_on_cloth.toml; do
  n=$(basename $P .toml)
  for B in msdsim_base msdsim_new; do
    mkdir -p /tmp/$B; .gl/$B simulate --preset $P --frames 40 --quiet --record /tmp/$B/$n.pc2 2>&1 | grep -E "error"
    echo "$n $B $(cat /tmp/$B/${n}_*.pc2 | md5sum)"
  done
done
# An experiment build (msdsim_skin: the batched build reading MSDSIM_SKIN, the contact lists'
# skin at least that many metres): lists that outlast more substeps.
for S in 0 0.001 0.002 0.004; do
  echo "== skin >= $S"
  MSDSIM_SKIN=$S .gl/msdsim_skin simulate --preset .gl/poker52.toml --frames 120 2>&1 | grep -E "GPU frame|GPU stage|error|contact between"
  MSDSIM_SKIN=$S .gl/msdsim_skin simulate --preset .gl/stack8.toml --frames 230 2>&1 | grep -E "GPU frame|error|contact between"
  MSDSIM_SKIN=$S .gl/msdsim_skin bench --filter "8 cloths 32x32, inter-object contact" --out $OUT/skin$S 2>&1 | grep "^| 8"
done
