# asm_add_module_headers_test(<module> <source dir>): the ctest test
# format.ModuleHeaders, which checks that the module's sources include only
# headers of the VTK modules it links (cmake/ASMCheckModuleHeaders.cmake).
#
# vtk_module_build() links a module to exactly the modules of its vtk.module's
# DEPENDS and PRIVATE_DEPENDS, so the target's LINK_LIBRARIES are those two
# lists (plus non-VTK libraries such as Eigen, which carry no
# INTERFACE_vtk_module_headers and are skipped). Each VTK module target records
# its installed headers in INTERFACE_vtk_module_headers; their file names are
# written to <build>/asm-dependency-headers.txt for the check script.
function (asm_add_module_headers_test module source_dir)
  get_target_property(_links "${module}" LINK_LIBRARIES)
  set(_headers)
  set(_modules)
  set(_missing)
  foreach (_link IN LISTS _links)
    if (NOT TARGET "${_link}")
      continue () # generator expressions and plain library names
    endif ()
    get_target_property(_link_headers "${_link}" INTERFACE_vtk_module_headers)
    get_target_property(_link_depends "${_link}" INTERFACE_vtk_module_depends)
    if (NOT _link_headers AND NOT _link_depends AND NOT "${_link}" MATCHES "^VTK::")
      continue () # not a VTK module (Eigen3::Eigen)
    endif ()
    if (NOT _link_headers)
      list(APPEND _missing "${_link}")
      continue ()
    endif ()
    list(APPEND _modules "${_link}")
    foreach (_header IN LISTS _link_headers)
      get_filename_component(_header "${_header}" NAME)
      list(APPEND _headers "${_header}")
    endforeach ()
  endforeach ()
  if (NOT _modules OR _missing)
    message(STATUS "ASM: no header list for ${_missing}; no format.ModuleHeaders test")
    return ()
  endif ()
  set(_list "${CMAKE_BINARY_DIR}/asm-dependency-headers.txt")
  file(WRITE "${_list}" "${_headers}")
  add_test(NAME format.ModuleHeaders
    COMMAND "${CMAKE_COMMAND}" "-DHEADERS_FILE=${_list}" "-DSOURCE_DIR=${source_dir}"
      -P "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/ASMCheckModuleHeaders.cmake")
  set_tests_properties(format.ModuleHeaders PROPERTIES LABELS format)
endfunction ()
