#!/bin/bash
# XPBD by Jacobi (step-bounded) against the spring classes and the other methods, fused and
# per stage; then the chart and the stability maps with all six methods.
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=.gl/msdsim; R=/tmp/xj2; mkdir -p $R/bench $R/chart $R/stability
bench() { # run method iterations sizes-args tag
  $B bench --frames 200 --warmup 30 $3 --filter "springs only" --integrator $1 --iterations $2 --out $R/bench/$4-$1-$2 > /dev/null 2>$R/bench/$4-$1-$2.err || echo "FAIL $4 $1 $2"
  grep "springs only" $R/bench/$4-$1-$2/bench.md | awk -v r="$4 $1-$2" -F'|' '{print r, $2, $4, $5, $6}'
}
for r in r1 r2; do
  for mi in "verlet 1" "xpbd 1" "xpbd_jacobi 1" "xpbd_jacobi 2" "implicit 4" "vbd 4"; do
    bench $mi "--cloth-sizes 32 --rope-sizes 256" f$r
  done
done
for r in r1 r2; do
  for mi in "verlet 1" "xpbd 1" "xpbd_jacobi 1" "xpbd_jacobi 2"; do
    bench $mi "--cloth-sizes 256,1024 --rope-sizes 65536" p$r
  done
done
s=$(date +%s); timeout 240 $B stability --out $R/stability > $R/stability/log.txt 2>&1; echo "stability rc=$? in $(( $(date +%s) - s )) s"
s=$(date +%s); timeout 300 $B chart --substeps 1,2,4,8,16,32,64,128,256 --iterations 1,4,10 --reference-substeps 2048 --out $R/chart > $R/chart/log.txt 2>&1; echo "chart rc=$? in $(( $(date +%s) - s )) s"
tail -3 $R/stability/log.txt; tail -5 $R/chart/log.txt
tar czf $OUT/xj2.tgz -C /tmp xj2
