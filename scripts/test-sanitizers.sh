#!/usr/bin/env bash
# Builds the module and the C++ tests a second time with AddressSanitizer,
# UndefinedBehaviorSanitizer and LeakSanitizer (build-asan/), and runs the
# C++ tests there: any report fails the run. No plugin or Python wrapping
# (ParaView's own libraries are not instrumented).
#
# This build also checks the plain-VTK path against the oldest VTK the module
# supports: it is configured without ParaView (-DASM_USE_PARAVIEW=OFF),
# against Debian 12's own VTK 9.1 (unpacked by scripts/fetch-vtk91.sh, since
# Debian cannot install it next to ParaView), whose default vtkSMPTools
# backend is TBB. So the module and its tests must build and link with VTK
# 9.1's modules alone, and the threading tests run TBB as well as STDThread.
# ASM_VTK_DIR picks another VTK (e.g. ParaView's VTK 9.2 used as a plain VTK:
# /usr/lib/x86_64-linux-gnu/cmake/paraview-5.11/vtk).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/install-deps.sh

if [ -n "${ASM_VTK_DIR:-}" ]; then
  vtk_dir="$ASM_VTK_DIR"
else
  . scripts/vtk91-env.sh
  vtk_dir="$ASM_VTK91_DIR"
fi

flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DASM_USE_PARAVIEW=OFF -DVTK_DIR="$vtk_dir" -DASM_BUILD_PLUGIN=OFF -DASM_WRAP_PYTHON=OFF \
  -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" "$@"
cmake --build build-asan --parallel "$(nproc)"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan -L cxx --output-on-failure
