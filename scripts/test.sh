#!/usr/bin/env bash
# Builds everything and runs the whole suite (unit, integration, gui, fuzz) with ctest. GUI tests need
# an X server, so ctest runs under Xvfb; -noreset because Xvfb otherwise resets when its last client
# disconnects, and a GUI test connecting during the reset (ctest runs two at once) fails to open the display.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
cd build
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest -j"$(nproc)" --output-on-failure "$@"
