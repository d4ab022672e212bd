set -u
nvidia-smi --query-gpu=name --format=csv,noheader
for f in .gl/c1/*.deb; do dpkg -x $f / >/dev/null; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
cd .gl/c1
grep -n "^iterations" ../../presets/twist.toml
echo "== GPU exhaustive twist test"
time MSDSIM_VALIDATION=1 timeout 400 ./suite self_contact::the_twist_preset_never_passes_through_itself --exact --include-ignored --nocapture 2>&1 | grep -vE "^\s+[0-9]+:|^\s+at " | tail -12
