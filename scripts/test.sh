#!/usr/bin/env bash
# The test suite: installs missing system packages, then runs every test on the Vulkan device
# (on a machine without a GPU: Mesa's lavapipe) with validation and synchronization validation.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh test
exec cargo test --locked "$@"
