#!/usr/bin/env bash
# Installs the Debian 12 packages Vesalius builds and tests with, or the packages named after
# `--packages` (scripts/install-workflow-deps.sh). Idempotent: prints nothing when all packages are
# already there. With --check it installs nothing and exits 1 when a package is missing. Run as root (or
# with sudo available).
set -euo pipefail

check=false
if [ "${1:-}" = --check ]; then check=true; shift; fi

PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  libinsighttoolkit5-dev libdcmtk-dev libvtk9-dev libeigen3-dev libtet1.5-dev
  libopenvdb-dev libboost-iostreams-dev libsuitesparse-dev libopenblas-dev libtbb-dev
  nlohmann-json3-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev
  libx11-dev xvfb xauth clang libclang-rt-14-dev
)

if [ "${1:-}" = --packages ]; then shift; PACKAGES=("$@"); fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0
$check && exit 1

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "Installing ${#missing[@]} Debian packages: ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq >/dev/null
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
