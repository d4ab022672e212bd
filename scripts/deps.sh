#!/usr/bin/env bash
# Installs the Debian/Ubuntu packages msdsim needs for a purpose, or says exactly which are
# missing when it cannot install them. Usage: scripts/deps.sh run|test|bench
set -euo pipefail

build=(build-essential pkg-config libshaderc-dev)
vulkan=(libvulkan1 mesa-vulkan-drivers)
window=(libx11-6 libx11-xcb1 libxcursor1 libxi6 libxrandr2 libxkbcommon-x11-0)
case "${1:-test}" in
  run) wanted=("${build[@]}" "${vulkan[@]}" "${window[@]}") ;;
  bench) wanted=("${build[@]}" "${vulkan[@]}") ;;
  test) wanted=("${build[@]}" "${vulkan[@]}" "${window[@]}" vulkan-validationlayers xvfb xauth) ;;
  *) echo "usage: $0 run|test|bench" >&2; exit 2 ;;
esac

if ! command -v cargo >/dev/null; then
  echo "msdsim needs Rust (cargo): install it from https://rustup.rs, then run this again." >&2
  exit 1
fi
if ! command -v dpkg-query >/dev/null; then
  echo "Not a Debian/Ubuntu system: make sure these (or your distribution's equivalents) are installed: ${wanted[*]}" >&2
  exit 0
fi

missing=()
for p in "${wanted[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "Installing missing packages: ${missing[*]}" >&2
if [ "$(id -u)" -eq 0 ]; then sudo=(); elif command -v sudo >/dev/null; then sudo=(sudo); else
  echo "Missing packages and no root or sudo to install them; run as root: apt-get install ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
if ! { "${sudo[@]}" apt-get update -qq && "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"; } >&2; then
  echo "Could not install: ${missing[*]} (apt-get install ${missing[*]})" >&2
  exit 1
fi
