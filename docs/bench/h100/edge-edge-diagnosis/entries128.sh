set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
for rep in 1 2; do
for cfg in "msdsim .gl/old/glsl" "msdsim glsl32" "msdsim128 .gl/v128"; do
  set -- $cfg; bin=.gl/$1; v=$2; tag=$(echo $1$v | tr '/' '_')
  if [ "$v" = glsl32 ]; then v=.gl/v32; fi
  $bin bench --frames 60 --warmup 10 --cloth-sizes 1024 --rope-sizes 256 --filter "triangle" --shaders $v --out "$out/b$tag$rep" > /dev/null 2>&1
  grep -E "curtain|cloth 1024" "$out/b$tag$rep/bench.md" | cut -d'|' -f2,5,12 | sed "s/^/$tag: /"
  echo "$tag towel: $($bin simulate --preset presets/towel.toml --frames 300 --quiet --shaders $v 2>&1 | grep -E 'GPU frame time|error')"
done
done
