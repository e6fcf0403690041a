#!/usr/bin/env bash
# Builds the libFuzzer target of the ASM core with clang, ASan and UBSan
# (Testing/Fuzz, a separate CMake project, into build-fuzz/) and runs it from
# the seed corpus in Testing/Fuzz/corpus/simplify.
#
# Default (CI): a short, deterministic run (-seed=1, ASM_FUZZ_RUNS inputs,
# fresh scratch corpus). Extra arguments go to libFuzzer, e.g. a longer run:
#   bash scripts/fuzz.sh -runs=-1 -max_total_time=3600 -jobs=2
# A crash leaves crash-<sha1> in the current directory; replay it with
#   build-fuzz/fuzz_simplify crash-<sha1>
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/install-deps.sh

CXX=clang++-14 cmake -S Testing/Fuzz -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo
cmake --build build-fuzz --parallel "$(nproc)"

# The run grows a scratch copy of the corpus; the repository's seeds stay as they are.
work=build-fuzz/corpus
rm -rf "$work"
mkdir -p "$work"
cp Testing/Fuzz/corpus/simplify/* "$work"/

ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  build-fuzz/fuzz_simplify -seed=1 -runs="${ASM_FUZZ_RUNS:-6000}" -max_len=4096 \
    -timeout=20 -rss_limit_mb=2048 -print_final_stats=1 "$@" "$work"
