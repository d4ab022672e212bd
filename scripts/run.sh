#!/usr/bin/env bash
# Runs the msdsim app on the default scene: installs missing system packages, builds the release
# binary, opens the window. Extra arguments go to `msdsim app` (e.g. --preset presets/towel.toml).
# Without a display, use the headless command: cargo run --release -- simulate --preset FILE.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh run
exec cargo run --release --locked -- app "$@"
