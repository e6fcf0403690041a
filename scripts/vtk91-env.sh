# Sourced (". scripts/vtk91-env.sh", from the repository root): unpacks
# Debian's own VTK 9.1 if needed (scripts/fetch-vtk91.sh) and exports
#   ASM_VTK91_DIR    its CMake package directory (VTK_DIR)
#   LD_LIBRARY_PATH  + its libraries (not on the loader's path: GoogleTest's
#                    test listing at build time and every test need them)
#   PYTHONPATH       + its vtkmodules (for the Python tests)
ASM_VTK91_DIR=$(bash scripts/fetch-vtk91.sh)
export ASM_VTK91_DIR
_asm_vtk91_prefix="${ASM_VTK91_DIR%/lib/x86_64-linux-gnu/cmake/vtk-9.1}"
export LD_LIBRARY_PATH="$_asm_vtk91_prefix/lib/x86_64-linux-gnu${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export PYTHONPATH="$_asm_vtk91_prefix/lib/python3/dist-packages${PYTHONPATH:+:$PYTHONPATH}"
unset _asm_vtk91_prefix
