#!/usr/bin/env bash
# A/B on the H100: contact between objects dividing each contact by the largest count of its
# particles (.gl/msdsim-old, e9a0a0c) against mass splitting with the inelastic split
# (.gl/msdsim), interleaved, three runs each: the bench's 8 stacked cloths, the rope_on_cloth
# preset, and 8 stacked 16 x 16 cloths settling for 10 s (stack.toml; layers.py prints each
# cloth's middle 4 x 4 particles' mean and lowest height and its fastest particle).
# Run from the repository root on the device machine:
#   OUT=$OUT bash docs/bench/h100/contact-mass-splitting/run.sh
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
here=docs/bench/h100/contact-mass-splitting
out=${OUT:-/tmp/out}/runs; mkdir -p "$out"
for run in 1 2 3; do
  for b in old new; do
    bin=.gl/msdsim; [ $b = old ] && bin=.gl/msdsim-old
    $bin bench --frames 200 --warmup 30 --filter "8 cloths" --out $out/$b-$run > $out/$b-$run.log 2>&1
    echo "$b $run: $(grep -h '8 cloths' $out/$b-$run/bench.csv | cut -d, -f1-3,7-9 | tr '\n' ' ')"
    $bin simulate --preset presets/rope_on_cloth.toml --frames 600 --quiet 2>&1 | tail -1 | sed "s/^/$b $run rope_on_cloth: /"
    if [ $run = 1 ]; then
      $bin simulate --preset $here/stack.toml --frames 600 --quiet --out $out/stack-$b.json 2>&1 | tail -2 | sed "s/^/$b stack: /"
      echo "$b stack layers (name, mean y, lowest y, fastest): $(python3 $here/layers.py $out/stack-$b.json)"
    fi
  done
done
