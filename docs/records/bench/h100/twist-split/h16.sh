set -u
# e = 92b682d (find, apply and note passes split among 8 lanes), b = d954a72 (none split):
# the lanes' bit-for-bit test on the GPU, the twist's cost, the GPU twist test with validation,
# mesh cloth against a grid of its vertex count.
nvidia-smi --query-gpu=name --format=csv,noheader
for f in .gl/c1/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /tmp/nw; cd .gl/c1
for f in msdsim_b msdsim_e suite; do xz -dc $f.xz > /tmp/nw/$f; chmod +x /tmp/nw/$f; done
echo "== lanes test on the GPU, validation"
time MSDSIM_VALIDATION=1 timeout 120 /tmp/nw/suite self_contact::a_search_split_among_lanes_gives_the_state_of_one_lane --exact --include-ignored --nocapture 2>&1 | grep -vE "^\s+[0-9]+:|^\s+at " | tail -8
run() { b=$1; shift; echo "== $b $*" | cut -c1-110; timeout 60 /tmp/nw/msdsim_$b simulate --preset ../../presets/twist.toml --frames 300 --quiet "$@" 2>&1 | grep -E "GPU frame time|stage means|rror|blew|stretch" | cut -c1-200; }
run e; run b; run e; run b
echo "== GPU twist test, per stage, validation"
time MSDSIM_VALIDATION=1 timeout 200 /tmp/nw/suite self_contact::the_twist_preset_never_passes_through_itself --exact --include-ignored --nocapture 2>&1 | grep -vE "^\s+[0-9]+:|^\s+at " | tail -6
echo "== mesh cloth against a grid of its vertex count (256 x 256), e, three rounds"
run2() { echo "== $*" | cut -c1-120; timeout 40 /tmp/nw/msdsim_e simulate "$@" --quiet 2>&1 | grep -E "GPU frame time|error" | cut -c1-200; }
for rep in 1 2 3; do for p in grid quads tris; do run2 --preset $p.toml --frames 60 --set sim.max_strain=0; done; done
