# The curtain preset with triangle self-contact (fused), base and v4 interleaved twice.
# Run from the repository root on the device machine: bash docs/bench/h100/contact-overflow/run-order.sh
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
for v in .gl/base/glsl .gl/v4 .gl/base/glsl .gl/v4; do
 echo "$v $(.gl/msdsim simulate --preset presets/curtain.toml --frames 300 --quiet --shaders $v --set 'cloth.0.self_contact="triangles"' 2>&1 | grep -E 'GPU frame time')"
done
