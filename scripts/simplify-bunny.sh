#!/usr/bin/env bash
# The main job: builds (see build.sh), then simplifies the Stanford bunny to
# 5 % with the ParaView plugin in pvpython and writes asm-output.ply in the
# current directory. Arguments go to the script and are read against the
# current directory, e.g.: Testing/Data/kitten.ply out.ply --fraction 0.1
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

(cd "$root" && bash scripts/build.sh)
exec pvpython "$root/Examples/Python/simplify_bunny.py" "$@"
