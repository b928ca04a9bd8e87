#!/usr/bin/env bash
# `cmake --install` into a fresh prefix, then the installed programs used as a user would: they find the
# data they ship with beside themselves (shipped_data.h), not in the source or build tree; the full-body
# reference builds from the installed files alone; each 3D Slicer wrapper describes its command.
# Usage: install_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 source=$2
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$prefix" > "$prefix/install.log" || { cat "$prefix/install.log"; fail "cmake --install"; }
for program in vesalius vesalius-picker vesalius-poser; do
  [ -x "$prefix/bin/$program" ] || fail "no $prefix/bin/$program"
done
vesalius="$prefix/bin/vesalius"
echo "installed: $("$vesalius" --version)"

# No path of the source or build tree in the program: a release binary carries no testdata path.
for tree in "$source" "$build"; do
  if grep -q -a -F "$tree/" "$vesalius"; then fail "$vesalius holds the path $tree/"; fi
done

share="$prefix/share/vesalius"
# The defaults that name shipped files point into the prefix, and the files are there.
demo_scan=$("$vesalius" demo --help | sed -n 's/^ *--scan TEXT=\([^ ]*\).*/\1/p')
[ "$demo_scan" = "$share/data/ct-abdomen-pelvis/example_ct.nii.gz" ] || fail "demo's scan is '$demo_scan'"
templates=$("$vesalius" patient --help | sed -n 's/^ *--templates TEXT=\([^ ]*\).*/\1/p')
[ "$templates" = "$share/templates/organs" ] || fail "patient's templates are '$templates'"
for f in data/ct-abdomen-pelvis/example_ct.nii.gz data/ct-abdomen-pelvis/labels_total_v1.tsv \
         data/ct-abdomen-pelvis/example_seg_total_v1_for_example_ct.nii.gz data/body/default.mhskel \
         data/body/base.obj data/body/shapes/mh_neutral_body.obj data/skeleton-opensim/Rajagopal2016.osim \
         templates/organs/liver.obj templates/reference-organs/skin.obj; do
  [ -s "$share/$f" ] || fail "no $share/$f"
done
for folder in body skeleton-opensim ct-abdomen-pelvis motion; do
  [ -s "$share/data/$folder/SOURCE.md" ] || fail "the installed $folder has no SOURCE.md"
done
[ -s "$prefix/share/doc/vesalius/cli.md" ] || fail "no docs in $prefix/share/doc/vesalius"
# VESALIUS_SHARE_DIR takes the lookup elsewhere.
moved=$(VESALIUS_SHARE_DIR=/elsewhere "$vesalius" demo --help | sed -n 's/^ *--scan TEXT=\([^ ]*\).*/\1/p')
[ "$moved" = /elsewhere/data/ct-abdomen-pelvis/example_ct.nii.gz ] || fail "VESALIUS_SHARE_DIR gave '$moved'"

# The full-body reference from the installed sources alone, by its defaults (`patient` builds it the same
# way): the report names the files it read, in the prefix.
"$vesalius" reference full-body --progress none --organ-meshes "$share/templates/reference-organs" \
  --out "$prefix/reference" --report "$prefix/reference.json" > /dev/null
tissues=$(ls "$prefix/reference/tissues" | wc -l)
echo "full-body reference from the installed data: $tissues tissue files"
[ "$tissues" -gt 0 ] || fail "the reference has no tissues"
for f in data/body/shapes/mh_neutral_body.obj data/body/default.mhskel data/skeleton-opensim/Rajagopal2016.osim; do
  grep -q -F "\"$share/$f\"" "$prefix/reference.json" || fail "the reference did not read $share/$f"
done

# 3D Slicer's module factory runs each executable of a module path with --xml (docs/cli.md).
modules=$(find "$prefix" -type d -name slicer-modules)
[ -n "$modules" ] || fail "no slicer-modules folder"
count=0
for wrapper in "$modules"/*; do
  [ -x "$wrapper" ] || fail "$wrapper is not executable"
  command=$(basename "$wrapper" | sed 's/^vesalius-//; s/-/ /g')
  xml=$("$wrapper" --xml)
  [ "${xml:0:5}" = "<?xml" ] || fail "$wrapper --xml does not start with <?xml"
  grep -q -F "<title>Vesalius $command</title>" <<< "$xml" || fail "$wrapper describes another command"
  count=$((count + 1))
done
# Started through a link, as a module path holding links to the wrappers would.
ln -s "$modules/vesalius-segment" "$prefix/segment-link"
"$prefix/segment-link" --xml | grep -q -F "<title>Vesalius segment</title>" || fail "a link to a wrapper fails"
echo "Slicer CLI modules: $count wrappers, each describing its command"
[ "$count" -ge 10 ] || fail "$count Slicer wrappers"
echo "install tree: passed"
