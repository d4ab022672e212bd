#!/bin/sh
# Rope self-collision as capsules (its segment pairs through the self-contact passes) against
# node against node: main before the change (.gl/msdsimM, ffc3f0c) and the change
# (.gl/msdsimC), interleaved, a warm-up round (a fresh machine's first runs are slow for both
# binaries, up to 4x) then three runs each, on one device session. From the repository root
# on the device machine; the results are summarised in results.txt.
set -e
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
for run in 0 1 2 3; do
  for b in M C; do
    .gl/msdsim$b bench --frames 200 --warmup 30 --rope-sizes 256,4096,65536 --cloth-sizes 16 \
      --filter "rope" --out "$OUT/$b-matrix-$run" > /dev/null 2>&1
    .gl/msdsim$b simulate --preset presets/rope.toml --frames 300 --quiet > "$OUT/$b-rope-$run.txt" 2>&1
    .gl/msdsim$b simulate --preset presets/playground.toml --frames 300 --quiet > "$OUT/$b-playground-$run.txt" 2>&1
  done
done
cd "$OUT"
for run in 1 2 3; do
  for b in M C; do
    echo "== $b run $run"
    grep 'GPU frame' "$b-rope-$run.txt" | sed 's/^/rope preset: /'
    grep 'GPU frame' "$b-playground-$run.txt" | sed 's/^/playground: /'
    # case | path | median ms a frame (p10 - p90)
    grep '^[a-z]*,"rope' "$b-matrix-$run/bench.csv" |
      sed 's/^[a-z]*,"\([^"]*\)",[^,]*,[^,]*,\([^,]*\),[^,]*,\([^,]*\),\([^,]*\),\([^,]*\),.*/\1 | \2 | \3 (\4 - \5)/'
  done
done
