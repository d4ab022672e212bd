#!/bin/bash
# Same-session A/B (the final run, r38-*): per-stage contact lists with the on/off policy
# (.gl/msdsim, c73d7dc) against ad5ebbc (.gl/msdsim-old). r33-*: the first version, lists always
# on, the same cases, two runs. Run from the repository root on the GPU machine, .gl/ carried.
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /tmp/r38
for r in r1; do for b in old new; do
  B=.gl/msdsim; [ $b = old ] && B=.gl/msdsim-old
  $B bench --frames 200 --warmup 30 --cloth-sizes 256,1024 --rope-sizes 65536 --filter "self-collision" --out /tmp/r38/m-$r-$b > /dev/null 2>/tmp/r38/m-$r-$b.err || { echo "FAIL m $b"; tail -3 /tmp/r38/m-$r-$b.err; }
  grep "1024x1024\|256x256\|65536" /tmp/r38/m-$r-$b/bench.md | awk -v r="$r $b" -F'|' '{print r, $2, $5, $6, $11, $12}'
  $B bench --frames 200 --warmup 30 --cloth-sizes 50,128 --rope-sizes 1024 --per-stage --filter "self-collision" --out /tmp/r38/p-$r-$b > /dev/null 2>/tmp/r38/p-$r-$b.err || { echo "FAIL p $b"; tail -3 /tmp/r38/p-$r-$b.err; }
  grep "|" /tmp/r38/p-$r-$b/bench.md | grep -v "^| case\|---" | awk -v r="$r $b ps" -F'|' '{print r, $2, $5, $6, $11, $12}'
done; done
for b in old new; do
  B=.gl/msdsim; [ $b = old ] && B=.gl/msdsim-old
  $B bench --frames 1000 --warmup 100 --cloth-sizes 1024 --rope-sizes 256 --filter "1024x1024, + self" --out /tmp/r38/long-$b > /dev/null 2>&1 || echo "FAIL long $b"
  grep "1024x1024" /tmp/r38/long-$b/bench.md | awk -v r="long $b" -F'|' '{print r, $2, $5, $6, $11, $12}'
  for f in "256x256, + self" "256x256, springs"; do
  $B bench --frames 300 --warmup 3000 --cloth-sizes 256 --rope-sizes 256 --filter "$f" --out "/tmp/r38/settled-$b-${f:10:3}" > /dev/null 2>&1 || echo "FAIL settled $b"
  grep "256x256" "/tmp/r38/settled-$b-${f:10:3}/bench.md" | awk -v r="settled $b" -F'|' '{print r, $2, $5, $6, $11, $12}'
  done
done
tar czf $OUT/r38.tgz -C /tmp r38
