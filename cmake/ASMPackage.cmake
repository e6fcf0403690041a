# The installed CMake package "ASM" (included from the top-level CMakeLists.txt
# after vtk_module_build, which exports ASM::Filters into ASM-targets.cmake and
# writes ASM-vtk-module-properties.cmake into the same directory):
#
#   cmake --install build --prefix /opt/asm
#   cmake -S Examples/Cxx -B build-example -DCMAKE_PREFIX_PATH=/opt/asm
#
# ASM_CMAKE_DESTINATION (lib/cmake/ASM) is set at the top level. A consumer then does find_package(ASM) and links ASM::Filters.
include(CMakePackageConfigHelpers)

if (ASM_HAVE_PARAVIEW)
  set(ASM_VTK_FLAVOUR "ParaView ${ParaView_VERSION}'s VTK")
  set(ASM_INSTALL_PLUGIN_DIR "${CMAKE_INSTALL_LIBDIR}/${PARAVIEW_PLUGIN_SUBDIR}/ASM")
else ()
  set(ASM_VTK_FLAVOUR "VTK")
  set(ASM_INSTALL_PLUGIN_DIR "${CMAKE_INSTALL_LIBDIR}")
endif ()
if (DEFINED ASM_PYTHON_DESTINATION)
  set(ASM_INSTALL_PYTHON_DIR "${ASM_PYTHON_DESTINATION}")
else ()
  set(ASM_INSTALL_PYTHON_DIR "${CMAKE_INSTALL_LIBDIR}")
endif ()

# For the install tree only (the build tree is not a package prefix).
set(_asm_package_dir "${CMAKE_BINARY_DIR}/CMakeFiles/asm-package")
configure_package_config_file(
  "${CMAKE_CURRENT_LIST_DIR}/ASMConfig.cmake.in"
  "${_asm_package_dir}/ASMConfig.cmake"
  INSTALL_DESTINATION "${ASM_CMAKE_DESTINATION}"
  PATH_VARS CMAKE_INSTALL_INCLUDEDIR ASM_INSTALL_PLUGIN_DIR ASM_INSTALL_PYTHON_DIR)
write_basic_package_version_file(
  "${_asm_package_dir}/ASMConfigVersion.cmake"
  VERSION       "${PROJECT_VERSION}"
  COMPATIBILITY SameMinorVersion)
install(
  FILES
    "${_asm_package_dir}/ASMConfig.cmake"
    "${_asm_package_dir}/ASMConfigVersion.cmake"
  DESTINATION "${ASM_CMAKE_DESTINATION}"
  COMPONENT   development)
