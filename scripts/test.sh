#!/usr/bin/env bash
# Builds (see build.sh), then runs every test: GoogleTest (label cxx) and
# pvpython (label python). Extra arguments go to ctest, e.g. -L python.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/build.sh
ctest --test-dir build --output-on-failure "$@"
