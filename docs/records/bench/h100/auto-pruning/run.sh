#!/bin/bash
# Wall clock of integrator = "auto" on every shipped preset (simulate --frames 1), the binary
# before the calibration skipped settings that cannot win and took the 128-substep reference
# (BASE) against the one after (NEW), interleaved; the pick each made.
# Run from the project root on the device: docs/records/bench/h100/auto-pruning/run.sh BASE NEW OUT
base=$1; new=$2; out=$3; mkdir -p "$out"
for run in 1 2; do
  for p in presets/*.toml; do
    for which in base new; do
      bin=$base; [ $which = new ] && bin=$new
      s=$(date +%s%N)
      "$bin" simulate --preset "$p" --frames 1 --quiet --set 'sim.integrator="auto"' > "$out/log.txt" 2>&1
      rc=$?
      e=$(date +%s%N)
      pick=$(grep -o 'picked [^:]*: error [^ ]*' "$out/log.txt")
      echo "$(basename $p .toml) $which run=$run rc=$rc wall=$(( (e - s) / 1000000 )) ms $pick" | tee -a "$out/results.txt"
    done
  done
done
