# The towel and tablecloth presets with particle and triangle self-contact, interleaved,
# three runs each, 300 frames (5 s) from the preset's start: `simulate` GPU frame times.
# Run from the repository root on the device machine:
# bash docs/bench/h100/presets-triangles/run.sh
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
for run in 1 2 3; do
  for p in towel:towel tablecloth:tablecloth; do
    preset=${p%%:*}; cloth=${p##*:}
    for m in particles triangles; do
      echo "== $preset $m run $run"
      .gl/msdsim simulate --preset presets/$preset.toml --frames 300 --quiet \
        --set "cloth.$cloth.self_contact=\"$m\"" 2>&1 | grep -E "GPU frame time|GPU stage means|error"
    done
  done
done
