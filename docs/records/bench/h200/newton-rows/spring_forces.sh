# H200: add_spring_forces (the explicit methods' spring forces) with selects per stage and its
# branches kept fused, against the branches in both: the binary of fa8be63 as .gl/msdsimB (main,
# built-in GLSL) and .gl/v_sf3/glsl a copy of the next commit's glsl/ (sf3). Two rounds; the
# curtain case whose fused time sf (selects in both paths, branchfree.txt) made 2.5% slower, the
# 1024 x 1024 cloth (per stage) and symplectic Euler on Newton's cloth at 32 substeps (per stage).
# Output: spring_forces.txt (bench.csv columns: case, particles, substeps, path, frames, frame
# median, 10%, 90%, physics median, 10%, 90%, constraints ..., surface ...). Run from the
# repository root.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=.gl/msdsimB
$B bench --frames 100 --warmup 5 --cloth-sizes 50 --filter "springs only" --out /tmp/warm > /dev/null 2>&1
for rep in 1 2; do
  for v in main sf3; do
    sh=""; [ $v != main ] && sh="--shaders .gl/v_$v/glsl"
    timeout 100 $B bench $sh --frames 200 --warmup 20 --cloth-sizes 50 --rope-sizes 256 --filter "curtain 50x50, all features + ground" --out /tmp/c-$v-$rep > /dev/null 2>&1
    timeout 100 $B bench $sh --frames 100 --warmup 10 --cloth-sizes 1024 --rope-sizes 256 --filter "1024x1024, springs only" --out /tmp/l-$v-$rep > /dev/null 2>&1
    grep -h "curtain 50x50, all features\"\|curtain 50x50, all features + ground\|triangle and edge\|1024x1024, springs only" /tmp/c-$v-$rep/bench.csv /tmp/l-$v-$rep/bench.csv | cut -d, -f2- | sed "s/^/$v-$rep: /"
    out=$(timeout 120 $B simulate $sh --preset docs/records/bench/h200/newton-rows/cloth_hanging.toml --set sim.max_strain=0 --set sim.integrator=symplectic_euler --set sim.substeps=32 --frames 330 2>&1)
    echo "$v-$rep symplectic 65,33 per stage: $(echo "$out" | grep "^frame" | tail -300 | awk '{s+=$4} END {printf "%.3f", s/NR}')"
  done
done
grep -h "^case\|^kind" /tmp/c-main-1/bench.csv | head -1
