set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
for rep in 1 2; do
  for bin in msdsimN msdsimB; do
    tag=$bin-$rep
    for p in towel; do
      echo "$tag $p: $(timeout 120 .gl/$bin simulate --preset presets/$p.toml --frames 300 --quiet 2>&1 | grep -E 'GPU frame time|error')"
    done
    if [ $rep = 1 ]; then
    timeout 200 .gl/$bin bench --frames 100 --warmup 20 --cloth-sizes 1024 --rope-sizes 256 --filter "triangle" --out "$out/bench-$tag" > "$out/bench-$tag.log" 2>&1
    grep -E "^\| (curtain|cloth 1024|rope)" "$out/bench-$tag.log" | cut -d'|' -f2,5,6,8,12 | sed "s/^/$tag: /"
    fi
  done
done
