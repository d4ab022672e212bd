set -u
nvidia-smi --query-gpu=name --format=csv,noheader
for f in .gl/c1/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
cd .gl/c1
run() { b=$1; shift; echo "== $b $*" | cut -c1-110; timeout 100 ./msdsim_$b simulate --preset ../../presets/twist.toml --frames 300 --quiet "$@" 2>&1 | grep -E "GPU frame time|stage means|rror" | cut -c1-200; }
run a
run b --set sim.max_strain=0
run b --set 'cloth.twist.stiffness={structural=400.0,shear=80.0,bending=0.05}'
run b --set 'cloth.twist.stiffness={structural=1000.0,shear=200.0,bending=0.05}'
run b --set sim.iterations=8
run a
run b --set sim.max_strain=0
