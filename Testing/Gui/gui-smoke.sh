#!/usr/bin/env bash
# GUI smoke test (CTest gui.ParaViewSmoke): the real Qt `paraview` under Xvfb
# with the ASM plugin loaded, GuiSmoke.py applied, then the screenshot checked
# (not blank) with CheckImage.py.
#
#   Testing/Gui/gui-smoke.sh PLUGIN_DIR DATA_DIR OUT_DIR [paraview] [pvpython]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
plugin_dir=$1 data_dir=$2 out_dir=$3 paraview=${4:-paraview} pvpython=${5:-pvpython}

mkdir -p "$out_dir"
export ASM_DATA_DIR="$data_dir"
export ASM_GUI_SCREENSHOT="$out_dir/gui-smoke.png"
export ASM_GUI_RESULT="$out_dir/gui-smoke.txt"
rm -f "$ASM_GUI_SCREENSHOT" "$ASM_GUI_RESULT"

"$here/run-xvfb.sh" --timeout 240 "$paraview" --dr \
  --plugin-search-paths="$plugin_dir" --plugins=ASM \
  --script="$here/GuiSmoke.py" --exit || { echo "gui-smoke: paraview failed ($?)"; exit 1; }

cat "$ASM_GUI_RESULT" 2>/dev/null || { echo "gui-smoke: GuiSmoke.py did not run (no $ASM_GUI_RESULT)"; exit 1; }
grep -q "^GuiSmoke: OK$" "$ASM_GUI_RESULT" || { echo "gui-smoke: GuiSmoke.py failed"; exit 1; }
"$pvpython" "$here/../../Examples/Python/check_image.py" "$ASM_GUI_SCREENSHOT"
