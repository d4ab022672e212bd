#!/bin/bash
# Wall clock of integrator = "auto" on every shipped preset (simulate --frames 1) and of a plain
# 60-frame run, the binary before the context cached its compute pipelines (BASE, 38431ee)
# against the one after (NEW, 82a576a), interleaved, three rounds (the first a warm-up of a
# fresh machine); the pick each made and the plain run's GPU frame time.
# Run from the project root on the device: docs/records/bench/h100/pipeline-cache/run.sh BASE NEW OUT
base=$1; new=$2; out=$3; mkdir -p "$out"
for run in 1 2 3; do
  for p in presets/*.toml; do
    for which in base new; do
      bin=$base; [ $which = new ] && bin=$new
      s=$(date +%s%N)
      "$bin" simulate --preset "$p" --frames 1 --quiet --set 'sim.integrator="auto"' > "$out/log.txt" 2>&1
      rc=$?
      e=$(date +%s%N)
      pick=$(grep -o 'picked [^:]*: error [^ ]*' "$out/log.txt")
      s2=$(date +%s%N)
      "$bin" simulate --preset "$p" --frames 60 --quiet > "$out/log2.txt" 2>&1
      e2=$(date +%s%N)
      frame=$(grep -o 'GPU frame time: mean [0-9.]* ms, median [0-9.]*' "$out/log2.txt")
      echo "$(basename $p .toml) $which run=$run rc=$rc auto=$(( (e - s) / 1000000 )) ms [$pick] plain60=$(( (e2 - s2) / 1000000 )) ms [$frame]" | tee -a "$out/results.txt"
    done
  done
done
