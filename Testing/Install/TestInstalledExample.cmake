# Installs the build tree into ASM_PREFIX (fresh), then configures, builds and
# tests the separate project Examples/Cxx against that prefix. Every step must
# succeed. Run by the CTest test install.ExampleCxx (Testing/Install).
foreach (var ASM_BUILD_DIR ASM_PREFIX EXAMPLE_SOURCE_DIR EXAMPLE_BUILD_DIR ASM_TEST_DATA_DIR GENERATOR)
  if (NOT DEFINED ${var})
    message(FATAL_ERROR "TestInstalledExample.cmake: -D${var}=... missing")
  endif ()
endforeach ()

function (run what)
  message(STATUS "${what}: ${ARGN}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result)
  if (NOT result EQUAL 0)
    message(FATAL_ERROR "${what} failed (${result})")
  endif ()
endfunction ()

file(REMOVE_RECURSE "${ASM_PREFIX}" "${EXAMPLE_BUILD_DIR}")
run("install" "${CMAKE_COMMAND}" --install "${ASM_BUILD_DIR}" --prefix "${ASM_PREFIX}")
if (NOT EXISTS "${ASM_PREFIX}/lib/cmake/ASM/ASMConfig.cmake" AND
    NOT EXISTS "${ASM_PREFIX}/lib64/cmake/ASM/ASMConfig.cmake")
  file(GLOB_RECURSE _configs "${ASM_PREFIX}/*ASMConfig.cmake")
  if (NOT _configs)
    message(FATAL_ERROR "no ASMConfig.cmake under ${ASM_PREFIX}")
  endif ()
endif ()
run("configure" "${CMAKE_COMMAND}"
  -S "${EXAMPLE_SOURCE_DIR}" -B "${EXAMPLE_BUILD_DIR}" -G "${GENERATOR}"
  -DCMAKE_BUILD_TYPE=Release
  "-DCMAKE_C_COMPILER=${C_COMPILER}" "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}"
  "-DCMAKE_PREFIX_PATH=${ASM_PREFIX}"
  "-DASM_TEST_DATA_DIR=${ASM_TEST_DATA_DIR}")
run("build" "${CMAKE_COMMAND}" --build "${EXAMPLE_BUILD_DIR}" --parallel 2)
# The example must use the installed library, not the build tree's.
file(STRINGS "${EXAMPLE_BUILD_DIR}/CMakeCache.txt" _asm_dir REGEX "^ASM_DIR:")
if (NOT _asm_dir MATCHES "${ASM_PREFIX}")
  message(FATAL_ERROR "the example found ASM elsewhere: ${_asm_dir}")
endif ()
run("test" "${CMAKE_CTEST_COMMAND}" --test-dir "${EXAMPLE_BUILD_DIR}" --output-on-failure)
run("bunny" "${EXAMPLE_BUILD_DIR}/asm_simplify"
  "${ASM_TEST_DATA_DIR}/bunny.ply" "${EXAMPLE_BUILD_DIR}/bunny-5pct.vtp" --fraction 0.05)
