#!/usr/bin/env bash
# Builds and runs the speed benchmark (issue 8): ASM's modes (curvature off
# and on) vs vtkVoxelGrid (count-matched) and vtkMaskPoints (random, exact
# count), 1 and 2 threads, N_s = 5 %, 1 %, 20 %, median of 5 runs, peak memory.
# Inputs: the bundled scans, ../shared/data/bunny-scans.ply when present, and
# the synthetic bumpy sphere at 100k, 1M, 4M, 14M points. The full run takes
# a long while (the 14M cloud alone is several minutes); extra arguments go
# to the program, e.g. --fractions 0.05 --inputs bumps:1M,bumps:4M, or --quick.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

if [ ! -f build/build.ninja ]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
fi
cmake --build build --parallel 2 --target asm_speed_benchmark

extra=()
[ -f ../shared/data/bunny-scans.ply ] && extra+=(../shared/data/bunny-scans.ply)
exec build/bin/asm_speed_benchmark "$@" "${extra[@]}"
