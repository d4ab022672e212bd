set -u
# Twist cost: b = d954a72's tree, c = the note pass split among 8 lanes (per stage), d = c with
# edge-pair cloths fused (the truncation from the contact lists); crossings with validation.
nvidia-smi --query-gpu=name --format=csv,noheader
for f in .gl/c1/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /tmp/nw; cd .gl/c1
for f in msdsim_b msdsim_c msdsim_d suite; do xz -dc $f.xz > /tmp/nw/$f; chmod +x /tmp/nw/$f; done
cp *.deb /tmp/nw/
run() { b=$1; shift; echo "== $b $*" | cut -c1-110; timeout 100 /tmp/nw/msdsim_$b simulate --preset ../../presets/twist.toml --frames 300 --quiet "$@" 2>&1 | grep -E "GPU frame time|stage means|rror|blew|stretch" | cut -c1-200; }
run b; run c; run d; run b; run c; run d
echo "== d per frame (every 25th)"
timeout 100 /tmp/nw/msdsim_d simulate --preset ../../presets/twist.toml --frames 300 2>&1 | awk 'NR%25==1' | cut -c1-150
echo "== GPU twist test, fused and per stage, validation"
time MSDSIM_VALIDATION=1 timeout 400 /tmp/nw/suite self_contact::the_twist_preset_never_passes_through_itself --exact --include-ignored --nocapture 2>&1 | grep -vE "^\s+[0-9]+:|^\s+at " | tail -12
