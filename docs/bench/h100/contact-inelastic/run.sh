#!/usr/bin/env bash
# A/B on the H100: contact between objects before (.gl/msdsim-old, 1493d40) and after the
# inelastic split (.gl/msdsim, 8c37d30: a second fixed-point sum, moves[] 8 words a particle,
# contact[] two vec4), interleaved, three runs each: the bench's 8 stacked cloths and the
# rope_on_cloth preset. Run from the repository root on the device machine:
#   OUT=$OUT bash docs/bench/h100/contact-inelastic/run.sh
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
for run in 1 2 3; do
  for b in old new; do
    bin=.gl/msdsim; [ $b = old ] && bin=.gl/msdsim-old
    $bin bench --frames 200 --warmup 30 --filter "8 cloths" --out $out/$b-$run > $out/$b-$run.log 2>&1
    echo "$b $run: $(grep -h '8 cloths' $out/$b-$run/bench.csv | cut -d, -f1-3,7-9 | tr '\n' ' ')"
    $bin simulate --preset presets/rope_on_cloth.toml --frames 600 --quiet 2>&1 | tail -1 | sed "s/^/$b $run rope_on_cloth: /"
  done
done
