#!/bin/bash
# Issue 68/71 on the H200 with 9faf7ef's release binary: the twist preset, the rigid start's
# cost (8 free stiff 32 x 32 VBD cloths at one substep against the same held at their corners),
# the stability map and the stiff chart.
for f in .gl/c1/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
chmod +x .gl/c1/msdsim_new; mkdir -p /tmp/nw; cp .gl/c1/part00 .gl/c1/msdsim_new .gl/c1/*.deb /tmp/nw/; mv /tmp/nw/msdsim_new /tmp/nw/msdsim
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
N=.gl/c1/msdsim_new
g() { grep -E "GPU frame|GPU stage|error" | cut -c1-160; }
for r in 1 2 3; do echo "== twist $r"; timeout 60 $N simulate --preset presets/twist.toml --frames 300 --quiet 2>&1 | g; done
for r in 1 2; do for p in free8 held8; do echo "== $p $r"; timeout 60 $N simulate --preset .gl/c1/$p.toml --frames 300 --quiet 2>&1 | g; done; done
for p in free8 held8; do echo "== $p implicit"; timeout 60 $N simulate --preset .gl/c1/$p.toml --frames 300 --quiet --set sim.integrator=implicit 2>&1 | g; done
( time timeout 120 $N stability --out $OUT/stability > $OUT/stability.log 2>&1 ) 2>&1 | grep real
grep "stable in" $OUT/stability/stability.csv
( time timeout 200 $N chart --scenes stiff --substeps 1,2,4,8,16,128 --iterations 1,2,4,10,30,100 --reference-substeps 256 --out $OUT/chart-stiff > $OUT/chart-stiff.log 2>&1 ) 2>&1 | grep real
tail -3 $OUT/chart-stiff.log
