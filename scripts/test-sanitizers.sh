#!/usr/bin/env bash
# Builds the module and the C++ tests a second time with AddressSanitizer,
# UndefinedBehaviorSanitizer and LeakSanitizer (build-asan/), and runs the
# C++ tests there: any report fails the run. No plugin or Python wrapping
# (ParaView's own libraries are not instrumented).
#
# This build also checks the plain-VTK path: it is configured without
# ParaView (-DASM_USE_PARAVIEW=OFF), against ParaView's VTK used as a plain
# VTK (Debian cannot hold VTK's own packages next to ParaView's), so the
# module and its tests must build and link with VTK's modules alone.
# ASM_VTK_DIR picks another VTK.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/install-deps.sh

vtk_dir="${ASM_VTK_DIR:-/usr/lib/x86_64-linux-gnu/cmake/paraview-5.11/vtk}"

flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DASM_USE_PARAVIEW=OFF -DVTK_DIR="$vtk_dir" -DASM_BUILD_PLUGIN=OFF -DASM_WRAP_PYTHON=OFF \
  -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" "$@"
cmake --build build-asan --parallel "$(nproc)"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan -L cxx --output-on-failure
