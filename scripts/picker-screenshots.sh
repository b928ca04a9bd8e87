#!/usr/bin/env bash
# Regenerates the screenshots of docs/picker.md with the picker itself, under Xvfb, on the shipped CT:
#   docs/images/picker-liver-fit.png     liver ICP markers and the fitted liver's contour
#   docs/images/picker-suggestions.png   suggested ICP markers (previews) around the placed template
# The markers, the fit and the suggestions are made here by the real commands (the fit takes a few
# minutes). Usage: scripts/picker-screenshots.sh [BUILD_DIR, default build] (built by scripts/build.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
vesalius=$build/apps/vesalius/vesalius
picker=$build/apps/vesalius-picker/vesalius-picker
for exe in "$vesalius" "$picker"; do
  [[ -x $exe ]] || { echo "picker-screenshots.sh: $exe is missing; run scripts/build.sh first" >&2; exit 2; }
done
ct=testdata/ct-abdomen-pelvis/example_ct.nii.gz
labels=testdata/ct-abdomen-pelvis/example_seg_total_v1_for_example_ct.nii.gz
table=testdata/ct-abdomen-pelvis/labels_total_v1.tsv
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p docs/images

"$vesalius" markers sample --labels "$labels" --table "$table" --label liver --count 150 --seed 7 \
  --out "$work/liver_icp.mrk.json"
"$vesalius" fit --template testdata/liver/liver.obj --icp "$work/liver_icp.mrk.json" --unattached \
  --target-tets 5000 --out "$work/liver_fitted.vtu" --surface-out "$work/liver_fitted.vtp" --progress none
"$vesalius" markers suggest --scan "$ct" --template testdata/liver/liver.obj --labels "$labels" --table "$table" \
  --label liver --count 80 --out "$work/liver_suggested.mrk.json" --placed-out "$work/liver_placed.vtp" \
  --progress none

# Shift+click on the liver in the coronal view (bottom left of a 1000x800 window, y up from the bottom)
# brings the axial and sagittal views to it; then the mouse rests there so the readout shows it.
cat >"$work/to_liver.events" <<'EOF'
# StreamVersion 1.1
LeftButtonPressEvent 150 330 1 0 0 0
LeftButtonReleaseEvent 150 330 1 0 0 0
MouseMoveEvent 150 330 0 0 0 0
EOF

shot() {  # markers overlay png
  xvfb-run -a -s "-screen 0 1280x1024x24" "$picker" "$ct" --markers "$1" --overlay "$2" \
    --out "$work/unused.mrk.json" --force --restore no --play "$work/to_liver.events" --exit-after-play \
    --screenshot "$3" --window-width 1000 --window-height 800
}
shot "$work/liver_icp.mrk.json" "$work/liver_fitted.vtp" docs/images/picker-liver-fit.png
shot "$work/liver_suggested.mrk.json" "$work/liver_placed.vtp" docs/images/picker-suggestions.png
ls -l docs/images/picker-*.png
