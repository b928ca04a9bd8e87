#!/usr/bin/env bash
# The main job: install, build the `vesalius` program (only it: the tests and benchmarks are test.sh's)
# and run `vesalius demo` on the shipped CT. Outputs go to demo-output/.
set -euo pipefail
cd "$(dirname "$0")/.."
VESALIUS_TARGETS=vesalius scripts/build.sh
build/apps/vesalius/vesalius demo --out demo-output --force "$@"
