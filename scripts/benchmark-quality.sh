#!/usr/bin/env bash
# Builds and runs the quality benchmark (issue 7): ASM's modes vs
# vtkVoxelGrid, vtkMaskPoints (random, stratified) and CGAL's grid and
# hierarchy simplifiers at N_s = 1 %, 5 %, 20 % of each input.
# Inputs: the bundled scans, ../shared/data/*.ply when present (skipped when
# the name is already bundled), and the synthetic shapes with known feature
# points. Extra arguments go to the program, e.g. --markdown or --fractions 0.05.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

if [ ! -f build/build.ninja ]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
fi
cmake --build build --parallel 2 --target asm_quality_benchmark

shared=()
for f in ../shared/data/*.ply; do
  [ -f "$f" ] && shared+=("$f")
done
exec build/bin/asm_quality_benchmark "$@" "${shared[@]}"
