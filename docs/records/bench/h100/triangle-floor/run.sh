# H200: how far below issue 26's cost targets triangle self-contact can go in this design.
# Main's GLSL (as built in) against two variants that give wrong answers on purpose, to bound
# what any cheaper test or search could save: `notest` (self_triangles returns at once: the
# hash is built and its candidates visited, no triangle or edge pair tested, no list entry)
# and `nosearch` (listed_candidates returns at once: no candidate visited, no list walked;
# the find, apply, take and further passes, the hash's build and the rest of the substep
# stay). Run from the repository root with the stripped binary as .gl/msdsimC and the variant
# trees as .gl/v_notest/glsl and .gl/v_nosearch/glsl (each one line added to main's glsl/,
# results.txt here). Two interleaved rounds; bench output under $OUT.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
.gl/msdsimC bench --frames 100 --warmup 5 --cloth-sizes 50 --filter "springs only" --out /tmp/warm > /dev/null 2>&1
for case in "1024x1024, springs only" "1024x1024, + self-collision"; do
  timeout 100 .gl/msdsimC bench --frames 200 --warmup 30 --cloth-sizes 1024 --rope-sizes 16 --filter "$case" --out /tmp/ctx > /dev/null 2>&1
  grep -h "$case" /tmp/ctx/bench.csv | sed "s/^/context: /"
done
for rep in 1 2; do
  for v in main notest nosearch; do
    sh=""; [ $v != main ] && sh="--shaders .gl/v_$v/glsl"
    tag=$v-$rep
    timeout 100 .gl/msdsimC bench $sh --frames 200 --warmup 30 --cloth-sizes 50 --rope-sizes 16 --filter "curtain 50x50, all features, triangle self-contact" --out /tmp/c-$tag > /dev/null 2>&1
    grep -h "triangle self-contact" /tmp/c-$tag/bench.csv | sed "s/^/$tag: /"
    timeout 100 .gl/msdsimC bench $sh --frames 200 --warmup 30 --cloth-sizes 1024 --rope-sizes 16 --filter "1024x1024, + triangle self-contact" --out /tmp/l-$tag > /dev/null 2>&1
    grep -h "triangle self-contact" /tmp/l-$tag/bench.csv | sed "s/^/$tag: /"
  done
done
head -5 /tmp/l-main-1/bench.csv | grep "^#"
grep -h "^case" /tmp/l-main-1/bench.csv
