# The towel with triangle self-contact at 128 and 256 substeps, 24 x 24 to 40 x 40, fused, on
# the H100: does it run away as on lavapipe? .gl/msdsim is the release build of 9197f7b;
# .gl/exp/msdsim256 the same with MAX_THREADS = 256 in src/sim/gpu/fused.rs (more particles a
# thread). Run from the repository root on the device machine. Output (2026-11-26, NVIDIA H100
# 80GB HBM3): every one of the 56 lines "simulated 1.0000 s in 60 frames (7680 substeps)" or
# "(15360 substeps)": none stopped.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
for b in .gl/msdsim .gl/exp/msdsim256; do
 for sub in 128 256; do
  for n in 24 28 30 32 33 36 40; do
    r=$($b simulate --preset presets/towel.toml --frames 60 --quiet --set sim.substeps=$sub \
      --set 'cloth.towel.self_contact="triangles"' --set "cloth.towel.resolution=[$n,$n]" 2>&1 | grep -E "error|simulated" | cut -c1-140)
    echo "$b sub=$sub n=$n: $r"
  done
 done
done
