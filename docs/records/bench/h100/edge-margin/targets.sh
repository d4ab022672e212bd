# H200: issue 26's cost targets with this build, two runs (the curtain with every feature, with
# particle and with triangle self-contact; the 1024 x 1024 cloth with particle and triangle
# self-contact). Run as run.sh.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
for rep in 1 2; do
  timeout 200 .gl/msdsimC bench --frames 200 --warmup 30 --cloth-sizes 1024 --rope-sizes 16 --filter "self-co" --out "$OUT/t-$rep" > "$OUT/t-$rep.log" 2>&1
  timeout 100 .gl/msdsimC bench --frames 200 --warmup 30 --cloth-sizes 50 --rope-sizes 16 --filter "curtain 50x50, all features" --out "$OUT/c-$rep" > "$OUT/c-$rep.log" 2>&1
  sed -n '/^| case/,/^$/p' "$OUT/t-$rep.log" "$OUT/c-$rep.log" | cut -d'|' -f2,4,5,6,7,12
done
