#!/bin/bash
# The guard's energy check (sim.max_energy_gain): wall clock of `simulate` with it on (the
# default 0.5) and off (0), interleaved, three runs each, on the H100.
# Run from the project root on the device: docs/records/bench/h100/energy-check/run.sh .gl/msdsim OUT
bin=$1; out=$2; mkdir -p "$out"
cases=(
  "curtain presets/curtain.toml 3000"
  "towel presets/towel.toml 3000"
  "cloth512 presets/curtain.toml 600 --set cloth.0.resolution=[512,512] --set sim.substeps=8 --set sim.max_strain=0"
)
for run in 1 2 3; do
  for c in "${cases[@]}"; do
    set -- $c; name=$1; preset=$2; frames=$3; shift 3
    for gain in 0.5 0; do
      s=$(date +%s%N)
      "$bin" simulate --preset "$preset" --frames "$frames" --quiet --set sim.max_energy_gain=$gain "$@" > "$out/log.txt" 2>&1
      rc=$?
      e=$(date +%s%N)
      gpu=$(grep "GPU frame time" "$out/log.txt" | sed 's/.*mean \([0-9.]*\) ms.*/\1/')
      [ $rc = 0 ] || tail -1 "$out/log.txt" >> "$out/results.txt"
      echo "$name gain=$gain run=$run rc=$rc wall=$(( (e - s) / 1000000 )) ms gpu_mean=$gpu ms" | tee -a "$out/results.txt"
    done
  done
done
