set -u
nvidia-smi --query-gpu=name --format=csv,noheader
for f in .gl/c1/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
cd .gl/c1
run() { b=$1; shift; echo "== $b $*"; ./msdsim_$b simulate "$@" --quiet 2>&1 | grep -E "GPU frame time|stage means|error"; }
for rep in 1 2 3; do for b in a b; do
  run $b --preset ../../presets/skirt.toml --frames 200
done; done
for b in a b; do run $b --preset ../../presets/holed_flag.toml --frames 200; done
