# Runs COMMAND (a list) and fails unless it exits non-zero AND its standard
# error matches EXPECT:  cmake "-DCOMMAND=prog;args" "-DEXPECT=regex" -P ExpectFailure.cmake
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("exit status: ${result}\nstdout:\n${out}\nstderr:\n${err}")
if (result EQUAL 0)
  message(FATAL_ERROR "expected a non-zero exit status")
endif ()
if (NOT err MATCHES "${EXPECT}")
  message(FATAL_ERROR "stderr does not match: ${EXPECT}")
endif ()
