# Triangle self-contact past PAIR_MAX contacts a particle: the 1024 x 1024 cloth of the bench
# from frame 220 on (folded, its contacts outgrow the 16 a particle keeps), one binary
# (.gl/msdsim) with GLSL trees named NAME=DIR. base: the GLSL before (8cc9c3a, .gl/base/glsl),
# whose apply pass searched the hash again for each further 16 contacts; v1: one search more,
# applying the contacts past the 16th as it finds them (.gl/v1, what landed); v2: contacts past
# the 16th dropped (.gl/v2, a bound on what the second search costs, not a candidate).
# Run from the repository root on the device machine: bash docs/bench/h100/contact-overflow/run.sh
set -u
[ $# -gt 0 ] || set -- base=.gl/base/glsl v4=.gl/v4
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
bin=.gl/msdsim
for run in ${RUNS:-1}; do
  for variant in "$@"; do
    v=${variant%%=*}; dir=${variant#*=}
    sh=""; [ -n "$dir" ] && sh="--shaders $dir"
    $bin bench --frames ${FRAMES:-100} --warmup ${WARMUP:-220} --cloth-sizes 1024 --rope-sizes 256 --filter "triangle" $sh --out "$out/$v-$run" > /dev/null 2>&1
    grep -E "triangle" "$out/$v-$run/bench.md" | cut -d"|" -f2,5,6,9,12 | sed "s/^/$v $run: /"
  done
done
