#!/usr/bin/env bash
# Builds the module and the C++ tests a second time with AddressSanitizer,
# UndefinedBehaviorSanitizer and LeakSanitizer (build-asan/), and runs the
# C++ tests there: any report fails the run. No plugin or Python wrapping
# (ParaView's own libraries are not instrumented).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/install-deps.sh

flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DASM_BUILD_PLUGIN=OFF -DASM_WRAP_PYTHON=OFF \
  -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" "$@"
cmake --build build-asan --parallel "$(nproc)"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan -L cxx --output-on-failure
