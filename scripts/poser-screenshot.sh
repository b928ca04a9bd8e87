#!/usr/bin/env bash
# Regenerates docs/images/poser.png with vesalius-poser itself, under Xvfb: MakeHuman's neutral body rigged
# by `vesalius rig` with its muscle surface as the tissue (the skin eroded by up to 1 cm of fat, `vesalius
# fat erode`), posed by CoR at frame 400 of the CMU motion 01_01, the skin translucent.
# Usage: scripts/poser-screenshot.sh [BUILD_DIR, default build] (built by scripts/build.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
vesalius=$build/apps/vesalius/vesalius
poser=$build/apps/vesalius-poser/vesalius-poser
for exe in "$vesalius" "$poser"; do
  [[ -x $exe ]] || { echo "poser-screenshot.sh: $exe is missing; run scripts/build.sh first" >&2; exit 2; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p docs/images

skin=testdata/body/shapes/mh_neutral_body.obj  # decimetres: 0.1 is 1 cm
"$vesalius" fat erode --skin "$skin" --thickness 0.1 --out "$work/muscles.obj"
"$vesalius" rig --skin "$skin" --skeleton testdata/body/default.mhskel --base-mesh testdata/body/base.obj \
  --tissue "$work/muscles.obj" --voxel-size 8 --target-tets 15000 --out "$work/rig"

printf '# StreamVersion 1.1\n' >"$work/nothing.events"
xvfb-run -a -s "-screen 0 1280x1024x24" "$poser" --anatomy "$work/rig" --motion testdata/motion/01_01.bvh \
  --frame 400 --method cor --play "$work/nothing.events" --exit-after-play --screenshot docs/images/poser.png \
  --window-width 900 --window-height 800
ls -l docs/images/poser.png
