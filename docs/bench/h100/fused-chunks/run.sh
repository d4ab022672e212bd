# The fused kernel's substeps from push constants (92568b0: a frame in chunks on lavapipe,
# one dispatch elsewhere) against the build before it (.gl/exp/msdsim-old, 2152a22's fused
# code), interleaved, three runs, 600 frames of each preset: `simulate` GPU frame times.
# Run from the repository root on the device machine: bash docs/bench/h100/fused-chunks/run.sh
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
for run in 1 2 3; do
  for b in .gl/exp/msdsim-old .gl/msdsim; do
    for p in towel rope curtain; do
      echo "== $p $b run $run"
      $b simulate --preset presets/$p.toml --frames 600 --quiet 2>&1 | grep -E "GPU frame time"
    done
  done
done
