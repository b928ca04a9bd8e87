#!/usr/bin/env bash
# The main job: install, build, and run `vesalius demo` on the shipped CT. Outputs go to demo-output/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
build/apps/vesalius/vesalius demo --out demo-output --force "$@"
