#!/usr/bin/env bash
# Checks, from the sources alone, the house rules docs/design.md states: the modules' includes point one
# way, ITK and VTK stay in the modules that may use them, no module includes an app, the commands of
# `vesalius` stay thin, and no document, comment, test or script carries a work diary (history belongs in
# git and CHANGELOG.md). Prints each breach on one line and exits 1 if there is any.
#
#   scripts/check-house.sh [ROOT]      (ROOT: the repository, by default this script's parent folder)
set -euo pipefail

root=${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}
cd "$root"
breaches=0
breach() {
  echo "house rules: $*" >&2
  breaches=$((breaches + 1))
}

# 1. Which modules each module may include (and itself): the graph of docs/design.md, "Dependencies".
declare -A may_use=(
  [core]=""
  [io]="core"
  [segmentation]="core"
  [meshing]="core io"
  [viz]="core io"
  [linalg]="core"
  [fem]="core linalg"
  [posing]="core linalg"
  [fit]="core linalg fem meshing"
  [fat]="core linalg meshing"
  [transfer]="core linalg meshing"
  [rigging]="core io meshing posing segmentation"
  [patient]="core io linalg meshing fem fit fat transfer posing rigging segmentation"
)
# ITK lives in io and segmentation; VTK in io, meshing, viz (and the apps).
itk_modules=" io segmentation "
vtk_modules=" io meshing viz "

module_dir() { if [ "$1" = segmentation ]; then echo segmentation; else echo "modules/$1"; fi; }

for dir in modules/*/; do
  m=$(basename "$dir")
  [ -n "${may_use[$m]+set}" ] || breach "$dir: a module docs/design.md and this script do not list"
done
for m in "${!may_use[@]}"; do
  dir=$(module_dir "$m")
  [ -d "$dir" ] || { breach "$dir: listed here but missing"; continue; }
  while IFS= read -r hit; do
    file=${hit%%:*}
    dep=$(sed -E 's/.*#include "vesalius\/([a-z_]+)\/.*/\1/' <<<"$hit")
    [ "$dep" = "$m" ] && continue
    case " ${may_use[$m]} " in
      *" $dep "*) ;;
      *) breach "$file: module $m includes $dep, which it may not use (docs/design.md)" ;;
    esac
  done < <(grep -rnE '^\s*#\s*include\s+"vesalius/[a-z_]+/' "$dir" || true)
  if [[ $itk_modules != *" $m "* ]]; then
    while IFS= read -r hit; do
      breach "${hit%%:*}: module $m includes ITK (only io and segmentation may)"
    done < <(grep -rnE '^\s*#\s*include\s+[<"]itk[A-Z]' "$dir" || true)
  fi
  if [[ $vtk_modules != *" $m "* ]]; then
    while IFS= read -r hit; do
      breach "${hit%%:*}: module $m includes VTK (only io, meshing, viz and the apps may)"
    done < <(grep -rnE '^\s*#\s*include\s+[<"]vtk[A-Z]' "$dir" || true)
  fi
  while IFS= read -r hit; do
    breach "${hit%%:*}: module $m includes an app's file"
  done < <(grep -rnE '^\s*#\s*include\s+"[^"]*apps/' "$dir" || true)
done

# 2. Thin commands: options, one library call, outputs. Commands still above the bound are listed here
# until their method code has moved into the modules; one that has shrunk below it must leave the list.
max_command_lines=300
still_thick=" "
for file in apps/vesalius/cmd_*.cpp; do
  name=$(basename "$file")
  lines=$(wc -l <"$file")
  if [[ $still_thick == *" $name "* ]]; then
    if [ "$lines" -le "$max_command_lines" ]; then
      breach "$file: $lines lines, within $max_command_lines: take it off this script's list of thick commands"
    else
      echo "house rules: $file is $lines lines, above $max_command_lines (listed: its method code is still to move)"
    fi
  elif [ "$lines" -gt "$max_command_lines" ]; then
    breach "$file: $lines lines, above $max_command_lines: move its method code into the module whose concept it is"
  fi
done

# 3. No work diary: the repository speaks of the software, its users and its methods, not of how it was
# made. CHANGELOG.md is where changes are told.
diary='\bsessions? [0-9]|work periods?\b|\bperiod [0-9]+\b|\bhelper-[0-9]|\bwas [0-9][0-9,.]*[^.;]{0,30}, now\b|\b(I|we) (tried|ran|changed|fixed)\b|\b(this|last|previous) session\b[^'"'"']'
# ... nor of whose other work shared the machine, of the change that made a figure, or of its tuning.
diary+='|\b(before|after) this (change|commit)\b|\bsince (commit )?[0-9a-f]{7,40}\b|\ba first run gave\b'
diary+='|\b(while|with) (two )?other (jobs|builds) (ran|were running|on the)|\bunder load from other\b'
diary+='|\bbeside other (runs|jobs|builds)\b|\bloaded by other\b|\bshared with (two|other) (builds|jobs)\b'
diary+='|\bas the [a-z]+ was tuned\b'
while IFS= read -r hit; do
  breach "${hit%%:*}: reads as a work diary: ${hit#*:}"
done < <(find README.md docs modules apps segmentation tests scripts templates workflows -type f \
           \( -name '*.md' -o -name '*.h' -o -name '*.cpp' -o -name '*.sh' -o -name '*.py' -o -name '*.txt' \
              -o -name 'Snakefile' -o -name '*.yaml' -o -name '*.cmake' \) \
           -not -path '*/corpus/*' -not -path 'scripts/check-house.sh' -print0 2>/dev/null |
         xargs -0 grep -nEiH "$diary" 2>/dev/null | cut -c1-200 || true)

if [ "$breaches" -gt 0 ]; then
  echo "house rules: $breaches breach(es)" >&2
  exit 1
fi
echo "house rules: the includes point one way, ITK and VTK where they belong, commands thin, no work diary"
