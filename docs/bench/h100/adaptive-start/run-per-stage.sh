#!/usr/bin/env bash
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
ab=$OUT/per-stage-ab.txt
for rep in 1 2 3; do
  for bin in msdsim-old msdsim; do
    for m in "vbd 4" "implicit 4" "vbd 10" "implicit 10"; do
      set -- $m
      echo "== $bin rep $rep cloth 256x256 $1 $2 per stage" >> $ab
      .gl/$bin simulate --preset presets/curtain.toml --frames 100 --quiet --set 'cloth.curtain.resolution=[256,256]' --set sim.max_strain=0 --set sim.integrator=$1 --set sim.iterations=$2 > /tmp/o.txt 2>&1
      grep -E "GPU frame time|GPU stage" /tmp/o.txt >> $ab || tail -5 /tmp/o.txt >> $ab
    done
  done
done
