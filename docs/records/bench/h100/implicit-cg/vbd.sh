#!/bin/bash
# Same session on the H100: VBD with its visit split into newton_particle and sym3_inverse
# (this build, .gl/msdsim-new) against a7bebdd's GLSL (--shaders .gl/base/glsl: `git archive
# a7bebdd glsl`, with obj.cheb_rho and obj.jacobi_damping renamed pad0 and pad1 so that the
# host's layout check accepts them), the same host; three interleaved runs. (run.sh's VBD
# part failed on that check.)
set -u
for f in .gl/*.deb; do dpkg -x $f / >/dev/null 2>&1; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
R=/tmp/vbd; mkdir -p $R
bench() {  # NAME ARGS...
  local name=$1; shift
  .gl/msdsim-new bench --frames 200 --warmup 30 --filter "springs only" --integrator vbd --iterations 4 "$@" --out $R/$name > /dev/null 2>&1 || echo "FAIL $name"
  grep "springs only" $R/$name/bench.md | awk -v r="$name" -F'|' '{print r, $2, $5, $6}'
}
for r in r1 r2 r3; do
  for v in base new; do
    S=""; [ $v = base ] && S="--shaders .gl/base/glsl"
    bench vf-$r-$v --cloth-sizes 32 --rope-sizes 256 $S
    bench vp-$r-$v --cloth-sizes 256,1024 --rope-sizes 65536 $S
  done
done
tar czf $OUT/vbd.tgz -C /tmp vbd
