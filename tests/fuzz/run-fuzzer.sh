#!/usr/bin/env bash
# run-fuzzer.sh FUZZER WORK_CORPUS SEED_CORPUS SECONDS
# Runs one libFuzzer harness for a bounded time. New inputs go to WORK_CORPUS (in the build tree);
# the seeds in the source tree are read, never written. A crash fails the test and leaves the input
# in the build tree as crash-*.
set -euo pipefail
fuzzer=$(realpath "$1") work=$(realpath -m "$2") seeds=$(realpath "$3") seconds=$4
mkdir -p "$work"
cd "$(dirname "$work")"
exec "$fuzzer" "$work" "$seeds" -max_total_time="$seconds" -seed=1 -max_len=65536 -timeout=10 \
  -rss_limit_mb=2048 -print_final_stats=1
