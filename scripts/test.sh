#!/usr/bin/env bash
# Builds everything and runs the whole suite (unit, integration, gui, fuzz) with ctest. GUI tests need
# an X server, so ctest runs under Xvfb.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
cd build
xvfb-run -a -s "-screen 0 1280x1024x24" ctest -j"$(nproc)" --output-on-failure "$@"
