#!/bin/bash
# Same-session A/B per stage: implicit Euler (1c4cb88, .gl/msdsim-old) against BDF2, springs only.
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /tmp/r32
for r in r1 r2; do for b in old new; do
  B=.gl/msdsim; [ $b = old ] && B=.gl/msdsim-old
  for mi in "verlet 4" "xpbd 1" "implicit 4" "vbd 4"; do
    set -- $mi
    $B bench --frames 100 --warmup 10 --cloth-sizes 256,1024 --rope-sizes 4096 --filter "springs only" --per-stage --integrator $1 --iterations $2 --out /tmp/r32/s-$r-$b-$1 > /dev/null 2>/tmp/r32/s-$r-$b-$1.err || { echo "FAIL staged $b $1"; tail -2 /tmp/r32/s-$r-$b-$1.err; }
    grep "cloth\|rope" /tmp/r32/s-$r-$b-$1/bench.md | awk -v r="$r $b $1" -F'|' '{print r, $2, $4, $5}'
    $B bench --frames 200 --warmup 30 --cloth-sizes 32 --rope-sizes 256 --filter "springs only" --integrator $1 --iterations $2 --out /tmp/r32/f-$r-$b-$1 > /dev/null 2>&1 || echo "FAIL fused $b $1"
    grep "cloth\|rope" /tmp/r32/f-$r-$b-$1/bench.md | awk -v r="$r $b $1" -F'|' '{print r, $2, $4, $5}'
  done
done; done
tar czf $OUT/r32.tgz -C /tmp r32
