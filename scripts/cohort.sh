#!/usr/bin/env bash
# Runs the cohort workflow (workflows/cohort/, Snakemake) on a folder of scans or a CSV sheet:
#   scripts/cohort.sh SCANS [snakemake options...]
# Locally with this machine's cores and memory, or on Slurm with
#   scripts/cohort.sh SCANS --profile workflows/cohort/profiles/slurm
# Outputs go to $COHORT_OUT (default ./cohort): patients/<scan>/, logs/, cohort.tsv, cohort.png. Run it
# again to go on where it stopped. Settings: --config key=value (workflows/cohort/config.yaml). The vesalius
# program: $VESALIUS, else vesalius on PATH, else build/apps/vesalius/vesalius. Installs Snakemake and Slurm
# (scripts/install-workflow-deps.sh) when they are missing.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
if [ $# -lt 1 ] || [ "${1:0:1}" = "-" ]; then
  sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
fi
scans=$(realpath "$1")
shift
"$repo/scripts/install-workflow-deps.sh"

out=$(realpath -m "${COHORT_OUT:-cohort}")
mkdir -p "$out"
if [ -z "${VESALIUS:-}" ] && ! command -v vesalius >/dev/null && [ -x "$repo/build/apps/vesalius/vesalius" ]; then
  export VESALIUS="$repo/build/apps/vesalius/vesalius"
fi

# scans=SCANS joins the user's own --config (Snakemake keeps only the last --config given).
args=()
joined=0
for a in "$@"; do
  args+=("$a")
  if [ $joined -eq 0 ] && { [ "$a" = --config ] || [ "$a" = -C ]; }; then
    args+=("scans=$scans")
    joined=1
  fi
done
[ $joined -eq 1 ] || args+=(--config "scans=$scans")

local_resources=()
case " $* " in
  *" --profile "* | *" --profile="*) ;;  # the profile says how many jobs and where
  *)
    mem_mb=$(awk '/^MemTotal:/ { printf "%d", $2 / 1024 * 0.9 }' /proc/meminfo)
    local_resources=(--cores "$(nproc)" --resources "mem_mb=$mem_mb")
    ;;
esac
# The caller's arguments first: --resources takes every word after it, a target such as `reference` too.
exec snakemake --snakefile "$repo/workflows/cohort/Snakefile" --directory "$out" --keep-going --rerun-incomplete \
  "${args[@]}" "${local_resources[@]}"
