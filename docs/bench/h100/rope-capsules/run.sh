# H100: contact between objects with ropes as capsules and mass splitting (f196e5f) against the
# GLSL before it (39a4a55's glsl/, through --shaders, in the same binary; the Rust side's larger
# contact-hash cells apply to both, so "before" may differ from 39a4a55 itself; not measured).
# Run from the repository root with the stripped binary as .gl/msdsimC and 39a4a55's glsl/ as
# .gl/glsl_main/glsl (docs/gpu-device.md's recipe).
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
for rep in 1 2 3; do
  for v in before after; do
    sh=""; [ $v = before ] && sh="--shaders .gl/glsl_main/glsl"
    for p in rope_on_cloth playground; do
      echo "$v-$rep $p: $(timeout 120 .gl/msdsimC simulate --preset presets/$p.toml --frames 300 --quiet $sh 2>&1 | grep -E 'GPU frame time|error' | tr '\n' ' ')"
    done
  done
done
