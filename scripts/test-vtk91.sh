#!/usr/bin/env bash
# Builds the module with its Python wrapping against Debian 12's own VTK 9.1
# (the oldest VTK the module supports; unpacked by scripts/fetch-vtk91.sh,
# since Debian cannot install it next to ParaView) in build-vtk91/, without
# ParaView, and runs the tests that the sanitizer build does not: the Python
# ones (the asmvtk package imported next to VTK 9.1's own vtkmodules) and
# the installed C++ example. The C++ tests run against this VTK in
# scripts/test-sanitizers.sh. Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/install-deps.sh
. scripts/vtk91-env.sh # its libraries and vtkmodules on the paths

cmake -S . -B build-vtk91 -G Ninja -DCMAKE_BUILD_TYPE=Release -DASM_USE_PARAVIEW=OFF \
  -DVTK_DIR="$ASM_VTK91_DIR" -DASM_WRAP_PYTHON=ON -DASM_BUILD_BENCHMARKS=OFF \
  -DPython3_EXECUTABLE=/usr/bin/python3
cmake --build build-vtk91 --parallel "$(nproc)"
ctest --test-dir build-vtk91 -L 'python|install' --output-on-failure "$@"
# The wrapping was built and tested, not skipped.
test -n "$(find build-vtk91 -path '*asmvtk/vtkASMFilters*.so' -print -quit)"
