#!/usr/bin/env bash
# The test suite: installs missing system packages, then runs every test on the Vulkan device
# (on a machine without a GPU: Mesa's lavapipe) with validation and synchronization validation.
# Extra arguments go to `cargo test`. Ends with one line of totals.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh test
log=$(mktemp)
trap 'rm -f "$log"' EXIT
status=0
cargo test --locked "$@" 2>&1 | tee "$log" || status=$?
awk '/^test result:/ { for (i = 1; i <= NF; i++) { if ($(i+1) ~ /^passed/) p += $i; if ($(i+1) ~ /^failed/) f += $i } }
     END { printf "%d passed, %d failed\n", p, f }' "$log"
exit "$status"
