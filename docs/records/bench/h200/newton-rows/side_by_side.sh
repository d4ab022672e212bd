# H200: issue 31's rows side by side, Newton 1.8.0 (warp-lang 1.19.0, wheels installed under
# /tmp/site) and msdsim (.gl/msdsimN, run.sh's preset and rows), interleaved, two rounds.
# Run from the repository root once the wheels are installed (see results.txt).
set -u
export PYTHONPATH=/tmp/site PYTHONUNBUFFERED=1
D=docs/records/bench/h200/newton-rows
for rep in 1 2; do
  for s in xpbd vbd vbd_noself semi_implicit; do
    timeout 240 python3 $D/newton_rows.py $s 300 2>&1 | grep -E "^newton|Error|error" | sed "s/^/rep $rep: /"
  done
  REPS=1 SIZES=65,33:6.4,3.2 bash $D/run.sh .gl/msdsimN 2>&1 | sed "s/^rep 1/rep $rep/"
done
