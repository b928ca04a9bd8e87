#!/usr/bin/env bash
# The workflow tests' fixture: installs Snakemake, Slurm and MUNGE (scripts/install-workflow-deps.sh),
# or says in one line why it cannot (exit 77, ctest's skip) and the workflow tests then skip too.
set -uo pipefail
install="$1/scripts/install-workflow-deps.sh"
if "$install" --check 2>/dev/null; then exit 0; fi
if [ "$(id -u)" -ne 0 ] && ! sudo -n true 2>/dev/null; then
  echo "SKIPPED: the workflow packages (snakemake, slurm-wlm, munge) are missing and installing needs root or sudo"
  exit 77
fi
if ! "$install"; then
  echo "SKIPPED: scripts/install-workflow-deps.sh could not install the workflow packages (no package source?)"
  exit 77
fi
