#!/usr/bin/env bash
# Installs the Debian 12 packages the cohort workflow (workflows/cohort/) runs with: Snakemake, Slurm and
# MUNGE (its authentication), matplotlib for the summary's plot. Idempotent: prints nothing when all
# packages are already there. Run as root (or with sudo available). scripts/install-deps.sh does not
# call it: the library and its tests need none of these. With --check it installs nothing and exits 1
# when a package is missing.
set -euo pipefail

exec "$(dirname "$0")/install-deps.sh" ${1:+"$1"} --packages snakemake python3-matplotlib slurm-wlm munge
