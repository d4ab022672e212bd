#!/usr/bin/env bash
# A/B on the H100: contact between objects before (msdsim-old, 10720ed: particles only) and
# after (particles against cloth triangles, with friction between objects), interleaved, three runs each.
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
cd "$(dirname "$0")/.."
for run in 1 2 3; do
  for b in old new; do
    bin=.gl/msdsim; [ $b = old ] && bin=.gl/msdsim-old
    $bin bench --frames 200 --warmup 30 --filter "8 cloths" --out $OUT/$b-$run > $OUT/$b-$run.log 2>&1
    echo "$b $run: $(grep -h '8 cloths' $OUT/$b-$run/bench.csv | cut -d, -f1-3,7-9 | tr '\n' ' ')"
    $bin simulate --preset presets/rope_on_cloth.toml --frames 600 --quiet 2>&1 | tail -1 | sed "s/^/$b $run rope_on_cloth: /"
  done
done
