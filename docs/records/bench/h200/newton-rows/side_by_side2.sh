# H200: issue 31's rows side by side again (2026-11-29, second session): Newton 1.8.0 (warp-lang
# 1.19.0, wheels installed under /tmp/site) and msdsim (.gl/msdsimE), interleaved. ROUND=1 or 2
# runs a round of the 64 x 32 rows (newton_rows.py, run.sh's rows on 65 x 33); LARGE=1 the
# 1024 x 1024 rows: Newton's XPBD and VBD (no self-contact) at 20 frames after 20, ours on
# 1025 x 1025 particles (0.1 m cells, the same preset) per stage, the mean of the last 40 of
# 60 frames (LARGE alone in a call: Newton's VBD at this size takes over four minutes to start).
# Run from the repository root once the wheels are installed; output in results2.txt.
set -u
export PYTHONPATH=/tmp/site PYTHONUNBUFFERED=1
D=docs/records/bench/h200/newton-rows
B=.gl/msdsimE
for rep in ${ROUND:-}; do
  for s in xpbd vbd vbd_noself semi_implicit; do
    timeout 240 python3 $D/newton_rows.py $s 300 2>&1 | grep -E "^newton|Error|error" | sed "s/^/rep $rep: /"
  done
  REPS=1 SIZES=65,33:6.4,3.2 bash $D/run.sh $B 2>&1 | sed "s/^rep 1/rep $rep/"
done
if [ -n "${LARGE:-}" ]; then
  for s in xpbd vbd_noself; do
    timeout 500 python3 $D/newton_rows.py $s 20 1024 1024 2>&1 | grep -E "^newton|Error|error"
  done
  for m in xpbd vbd xpbd_jacobi; do
    out=$(timeout 200 $B simulate --preset $D/cloth_hanging.toml --set cloth.cloth.resolution=[1025,1025] \
      --set cloth.cloth.size=[102.4,102.4] --set sim.integrator=$m --set sim.max_strain=0 --frames 60 2>&1)
    last=$(echo "$out" | grep "^frame" | tail -40 | awk '{s+=$4} END {printf "%.3f (%d frames)", s/NR, NR}')
    echo "msdsimE 1025,1025 $m: last-40 mean $last ms $(echo "$out" | grep -i error | head -1)"
  done
fi
