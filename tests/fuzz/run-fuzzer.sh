#!/usr/bin/env bash
# run-fuzzer.sh FUZZER WORK_CORPUS SEED_CORPUS SECONDS
# Runs one libFuzzer harness for a bounded time. New inputs go to WORK_CORPUS (in the build tree);
# the seeds in the source tree are read, never written. A crash fails the test and leaves the input
# in the build tree as crash-*. -timeout is wall time and finds hangs: ctest runs the fuzzers beside the
# minutes-long tests, and on a loaded 2-core machine fuzz_mha has run at a tenth of its speed alone
# (234 inputs a second against 2,400) and had one input pass 10 s.
set -euo pipefail
fuzzer=$(realpath "$1") work=$(realpath -m "$2") seeds=$(realpath "$3") seconds=$4
mkdir -p "$work"
cd "$(dirname "$work")"
exec "$fuzzer" "$work" "$seeds" -max_total_time="$seconds" -seed=1 -max_len=65536 -timeout=60 \
  -rss_limit_mb=2048 -print_final_stats=1
