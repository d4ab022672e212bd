#!/usr/bin/env bash
# One device call: the stiff-cloth matrix (new binary), then old/new A/B cost of the solver changes.
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
.gl/msdsim devices > $OUT/devices.txt 2>&1
start=$(date +%s)
.gl/stiff-cloth.sh .gl/msdsim .gl/stiff-cloth.toml /tmp/stiff
echo "matrix took $(( $(date +%s) - start )) s" > $OUT/timing.txt
tar czf $OUT/stiff.tgz -C /tmp stiff
ab=$OUT/ab.txt
for rep in 1 2 3; do
  for bin in msdsim-old msdsim; do
    for m in "vbd 10" "implicit 10" "vbd 4" "implicit 4"; do
      set -- $m
      echo "== $bin rep $rep curtain $1 $2 fused" >> $ab
      .gl/$bin simulate --preset presets/curtain.toml --frames 300 --quiet --set sim.integrator=$1 --set sim.iterations=$2 2>&1 | grep -E "GPU frame time|GPU stage|path" >> $ab
    done
    for m in "vbd 4" "implicit 4"; do
      set -- $m
      echo "== $bin rep $rep cloth256 $1 $2 per stage" >> $ab
      .gl/$bin simulate --preset presets/curtain.toml --frames 100 --quiet --set 'cloth.curtain.resolution=[256,256]' --set sim.integrator=$1 --set sim.iterations=$2 2>&1 | grep -E "GPU frame time|GPU stage" >> $ab
    done
  done
done
echo "all took $(( $(date +%s) - start )) s" >> $OUT/timing.txt
