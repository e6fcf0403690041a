#!/usr/bin/env bash
# Installs the Debian packages (if missing), configures and builds into build/.
# Extra arguments go to the CMake configure step, e.g.
#   bash scripts/build.sh -DASM_BUILD_PLUGIN=OFF
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/install-deps.sh

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build build --parallel "$(nproc)"
