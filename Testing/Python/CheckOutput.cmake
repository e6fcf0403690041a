# Runs a command and fails unless it exits with 0 AND its standard output
# matches a regular expression (CTest's PASS_REGULAR_EXPRESSION alone ignores
# the exit code). Used by the example smoke tests in CMakeLists.txt:
#
#   cmake "-DCHECK_COMMAND=prog;arg1;arg2" "-DCHECK_EXPECT=regex" -P CheckOutput.cmake
if (NOT CHECK_COMMAND OR NOT DEFINED CHECK_EXPECT)
  message(FATAL_ERROR "CheckOutput.cmake: pass -DCHECK_COMMAND=<list> and -DCHECK_EXPECT=<regex>")
endif ()

execute_process(
  COMMAND         ${CHECK_COMMAND}
  RESULT_VARIABLE result
  OUTPUT_VARIABLE output
  ERROR_VARIABLE  errors)
message("${output}")
if (errors)
  message("stderr:\n${errors}")
endif ()
if (NOT result EQUAL 0)
  message(FATAL_ERROR "exit status ${result} (expected 0)")
endif ()
if (NOT output MATCHES "${CHECK_EXPECT}")
  message(FATAL_ERROR "output does not match: ${CHECK_EXPECT}")
endif ()
