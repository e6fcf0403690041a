#!/usr/bin/env bash
# Builds and runs the speed benchmark (issue 8): ASM's modes (curvature off
# and on) vs vtkVoxelGrid (count-matched) and vtkMaskPoints (random, exact
# count), 1 and 2 threads, N_s = 5 %, 1 %, 20 %, median of 5 runs, peak memory.
# Inputs: the bundled scans, ../shared/data/bunny-scans.ply when present, and
# the synthetic bumpy sphere at 100k, 1M, 4M, 14M points. The full run takes
# a long while (the 14M cloud alone is several minutes); extra arguments go
# to the program, e.g. --fractions 0.05 --inputs bumps:1M,bumps:4M, or --quick.
#   bash scripts/benchmark-speed.sh --vtk91 --readme --markdown   # the README's table and targets (~7 min idle)
#   bash scripts/benchmark-speed.sh --readme --markdown           # the same against ParaView's VTK
#
# --vtk91 (first argument) builds and runs against Debian's own VTK 9.1
# (scripts/fetch-vtk91.sh; build-vtk91-bench/): Debian's ParaView 5.11 libraries,
# VTK's included, are compiled without optimization, so vtkVoxelGrid and
# vtkMaskPoints run 3.6-4.5 times slower there than in an optimized VTK (see
# the README, "Benchmark: speed"); ASM itself is built optimized either way.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

build=build
if [ "${1:-}" = "--vtk91" ]; then
  shift
  . scripts/vtk91-env.sh
  build=build-vtk91-bench
  if [ ! -f "$build/build.ninja" ]; then
    cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DASM_USE_PARAVIEW=OFF \
      -DVTK_DIR="$ASM_VTK91_DIR" -DASM_WRAP_PYTHON=OFF -DBUILD_TESTING=OFF -DASM_BUILD_BENCHMARKS=ON
  fi
elif [ ! -f build/build.ninja ]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
fi
cmake --build "$build" --parallel 2 --target asm_speed_benchmark

extra=()
# (--readme and --quick choose their own inputs; --readme includes bunny-scans)
case " $* " in
  *" --readme "*|*" --quick "*) ;;
  *) [ -f ../shared/data/bunny-scans.ply ] && extra+=(../shared/data/bunny-scans.ply) ;;
esac
exec "$build/bin/asm_speed_benchmark" "$@" "${extra[@]}"
