#!/usr/bin/env bash
# The main job: builds (see build.sh), then simplifies the Stanford bunny to
# 5 % with the ParaView plugin in pvpython and writes asm-output.ply.
# Arguments go to the script, e.g.: Testing/Data/kitten.ply out.ply --fraction 0.1
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/build.sh
pvpython Examples/Python/simplify_bunny.py "$@"
