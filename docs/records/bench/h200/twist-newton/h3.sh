set -u
# Newton's cloth_twist against msdsim's twist preset in one lease (x = 229dfe6's tree).
cp .gl/nw2/part02 /tmp/nw/ && cd /tmp/nw && cat part0* | xz -d | tar x && cd - >/dev/null
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
nvidia-smi --query-gpu=name --format=csv,noheader
m() { echo "== msdsim_x twist $*"; timeout 90 /tmp/nw/msdsim_x simulate --preset presets/twist.toml --frames 300 --quiet "$@" 2>&1 | grep -E "GPU frame|error" | cut -c1-160; }
m; m
PYTHONPATH=/tmp/nw/site timeout 300 python3 .gl/nw2/bench_twist.py --quiet --repeats 2 2>&1 | grep -E "RESULT|Error|error" | head -20
m; m
