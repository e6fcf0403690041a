#!/usr/bin/env bash
# CTest gui.PaperFigures: renders Examples/Python/paper_figures.py (600x400)
# with pvbatch under Xvfb + llvmpipe and compares it with the baseline
# Testing/Data/Baseline/paper_figures.png (check_image.py: not blank, mean
# absolute pixel difference <= 3 on a 0-255 scale).
#
#   Testing/Gui/paper-figures.sh PLUGIN OUT_DIR [pvbatch] [pvpython]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$here/../.."
plugin=$1 out_dir=$2 pvbatch=${3:-pvbatch} pvpython=${4:-pvpython}
mkdir -p "$out_dir"
out="$out_dir/paper_figures.png"
rm -f "$out"
"$here/run-xvfb.sh" --timeout 240 "$pvbatch" "$repo/Examples/Python/paper_figures.py" \
  --plugin "$plugin" --size 600 400 -o "$out"
"$pvpython" "$repo/Examples/Python/check_image.py" "$out" \
  --baseline "$repo/Testing/Data/Baseline/paper_figures.png" --tolerance 3
