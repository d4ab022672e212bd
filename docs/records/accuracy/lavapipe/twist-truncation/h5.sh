set -u
# The twist preset with the edge pairs' truncation (b: this build, its preset) against main's
# build (a: 50d0fb2's code, 8c300fe's binary) with triangles alone (the preset as main had it)
# and with edges (main's bound on each move), interleaved; then the towel (triangles: nothing
# changed) on both.
nvidia-smi --query-gpu=name --format=csv,noheader
for f in .gl/c1/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
cd .gl/c1
run() { b=$1; shift; echo "== $b $*"; timeout 100 ./msdsim_$b simulate "$@" --quiet 2>&1 | grep -E "GPU frame time|stage means|error|rror"; }
T=../../presets/twist.toml
for rep in 1 2 3; do
  run b --preset $T --frames 300
  run a --preset $T --frames 300 --set 'cloth.twist.self_contact="triangles"'
  run a --preset $T --frames 300
  run b --preset $T --frames 300 --set 'cloth.twist.self_contact="triangles"'
done
for rep in 1 2; do for b in a b; do run $b --preset ../../presets/towel.toml --frames 300; done; done
