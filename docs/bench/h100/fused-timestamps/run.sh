# Stage timing with every object fused: two timestamps after the pass (47b1ffc) against two a
# substep (the binary before, .gl/msdsim at 8cc9c3a). GPU time a frame from simulate, three
# interleaved runs each, the curtain and rope presets (fused on the H100).
# Run from the repository root on the device machine: bash docs/bench/h100/fused-timestamps/run.sh
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
for run in 1 2 3; do
  for bin in msdsim msdsim-new; do
    for p in curtain rope; do
      echo "$bin $run $p: $(.gl/$bin simulate --preset presets/$p.toml --frames 600 --quiet 2>&1 | grep -E 'GPU frame time|stage means' | tr '\n' ' ')"
    done
  done
done
