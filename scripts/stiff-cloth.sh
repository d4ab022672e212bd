#!/usr/bin/env bash
# The stiff cloth at large steps (docs/ACCURACY.md, "Large steps"): every iterative method at 1,
# 2 and 4 substeps a frame and 2 to 100 iterations, and Verlet at a stable substep count, on
# docs/records/accuracy/stiff/stiff-cloth.toml at 1e4 and 1e5 N/m, 240 frames (4 s) each. Writes, per
# run, the final state (NAME.json: the settled sag and speeds) and `simulate`'s summary
# (NAME.log: GPU time a frame) into OUT; scripts/stiff-cloth.py makes the table from them.
# Usage: scripts/stiff-cloth.sh MSDSIM_BINARY PRESET OUT
# METHODS (default: vbd implicit xpbd xpbd_jacobi) picks the iterative methods; VERLET=0 leaves
# Verlet's run out.
set -euo pipefail
bin=$1 preset=$2 out=$3
mkdir -p "$out"
run() {
  local name=$1; shift
  "$bin" simulate --preset "$preset" --frames 240 --quiet --out "$out/$name.json" "$@" > "$out/$name.log" 2>&1 ||
    echo "exit $?" >> "$out/$name.log"
}
for k in 1e4 1e5; do
  stiff=(--set "cloth.stiff.stiffness.structural=$k"
         --set "cloth.stiff.stiffness.shear=$(awk "BEGIN { print $k / 2 }")"
         --set "cloth.stiff.stiffness.bending=$(awk "BEGIN { print $k / 10 }")")
  # Verlet's stable limit (`simulate` predicts it): 95 substeps at 1e4 N/m, 299 at 1e5.
  verlet=$([ "$k" = 1e4 ] && echo 128 || echo 384)
  [ "${VERLET:-1}" = 0 ] || run "k$k-verlet-$verlet-1" "${stiff[@]}" --set sim.integrator=verlet --set "sim.substeps=$verlet"
  for method in ${METHODS:-vbd implicit xpbd xpbd_jacobi}; do
    for substeps in 1 2 4; do
      for iterations in 2 4 10 30 100; do
        run "k$k-$method-$substeps-$iterations" "${stiff[@]}" --set "sim.integrator=$method" \
          --set "sim.substeps=$substeps" --set "sim.iterations=$iterations"
      done
    done
  done
done
