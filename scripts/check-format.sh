#!/usr/bin/env bash
# Checks that the C++ sources follow .clang-format (VTK's style) with
# clang-format 14, the version Debian 12 ships (other versions format some
# constructs differently). Lists the files that differ and how to fix them.
#
#   scripts/check-format.sh [clang-format]     (CTest: format.ClangFormat)
#
# Exit status: 0 formatted, 1 not, 77 no clang-format 14 found (CTest: skipped).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

tool=${1:-}
if [ -z "$tool" ]; then
  tool=$(command -v clang-format-14 || command -v clang-format || true)
fi
if [ -z "$tool" ] || ! "$tool" --version | grep -q "version 14\."; then
  echo "check-format: clang-format 14 not found (apt-get install clang-format-14); not checked"
  exit 77
fi

if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files '*.cxx' '*.h')
else
  mapfile -t files < <(find Benchmarks Examples Filters Testing -name '*.cxx' -o -name '*.h' | sort)
fi

unformatted=()
for f in "${files[@]}"; do
  if ! "$tool" --style=file --dry-run -Werror "$f" >/dev/null 2>&1; then
    unformatted+=("$f")
  fi
done

if [ ${#unformatted[@]} -gt 0 ]; then
  echo "check-format: ${#unformatted[@]} of ${#files[@]} files differ from .clang-format:"
  printf '  %s\n' "${unformatted[@]}"
  echo "fix: $tool -i ${unformatted[*]}"
  exit 1
fi
echo "check-format: ${#files[@]} files formatted"
