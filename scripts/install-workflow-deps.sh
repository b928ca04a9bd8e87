#!/usr/bin/env bash
# Installs the Debian 12 packages the cohort workflow (workflows/cohort/) runs with: Snakemake, Slurm and
# MUNGE (its authentication), matplotlib for the summary's plot. Idempotent: prints nothing when all
# packages are already there. Run as root (or with sudo available). scripts/install-deps.sh does not
# call it: the library and its tests need none of these. With --check it installs nothing and exits 1
# when a package is missing.
set -euo pipefail

PACKAGES=(snakemake python3-matplotlib slurm-wlm munge)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0
[ "${1:-}" = --check ] && exit 1

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "Installing ${#missing[@]} Debian packages: ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq >/dev/null
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
