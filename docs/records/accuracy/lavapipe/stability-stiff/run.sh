#!/bin/bash
# Issue 68: the stability maps at the large-step settings: the stiff cloth of
# docs/records/accuracy/stiff/stiff-cloth.toml (12 x 12, 1 g particles, held at its corners,
# 1e4 N/m scaled over four decades by the map) against 1 to 64 substeps, the iterative methods,
# with the presets' light dashpots (0.01 N s/m) at 2 and 10 iterations and heavy ones (0.2,
# past b dt / m = 1) at 2. Release build of main 4033d64, lavapipe (the classification does not
# depend on the device), 120 frames a cell.
set -e
P=docs/records/accuracy/stiff/stiff-cloth.toml
M=xpbd,implicit,vbd,xpbd_jacobi
msdsim stability --preset $P --set cloth.stiff.damping=0.01 --set sim.iterations=2 --methods $M --out light-2
msdsim stability --preset $P --set cloth.stiff.damping=0.2 --set sim.iterations=2 --methods $M --out heavy-2
msdsim stability --preset $P --set cloth.stiff.damping=0.01 --set sim.iterations=10 --methods $M --out light-10
