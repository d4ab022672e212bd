# H200: VBD with triangle self-contact on the 65 x 33 cloth, every 15th frame's GPU time, main against
# the notest variant (breakdown_variants.py): where the triangle tests' cost comes from over the run.
# Run from the repository root after breakdown_variants.py. Output: frames.txt.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
P=docs/records/bench/h200/newton-rows/cloth_hanging.toml
B=.gl/msdsimN
tri="--set cloth.cloth.self_collision=true --set cloth.cloth.self_collision_distance=0.05"
$B simulate --preset $P --frames 60 --quiet > /dev/null 2>&1
for v in main notest; do
  sh=""; [ $v != main ] && sh="--shaders .gl/v_$v/glsl"
  $B simulate $sh --preset $P --set sim.max_strain=0 $tri --frames 330 2>&1 | grep "^frame" | awk -v v=$v '$2 % 15 == 0 {print v, $2, $4}'
done
