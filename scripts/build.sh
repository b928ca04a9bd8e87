#!/usr/bin/env bash
# Installs what is missing and builds Vesalius (Release) in build/: everything, or only the targets named
# with VESALIUS_TARGETS (e.g. VESALIUS_TARGETS=vesalius). Extra arguments go to cmake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
targets=()
for t in ${VESALIUS_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build build -j"$(nproc)" "${targets[@]}"
