#!/usr/bin/env bash
# Runs msdsim on the default scene: installs missing system packages, builds the release binary,
# then simulates presets/playground.toml headless for 10 s of simulated time. Extra arguments
# go to `msdsim simulate` (e.g. --out state.json).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh run
exec cargo run --release --locked -- simulate --preset presets/playground.toml --frames 600 --quiet "$@"
