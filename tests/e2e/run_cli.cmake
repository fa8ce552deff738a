# Runs semo-verify once in an empty working folder and checks its exit code, its output, and that it
# wrote no file. Variables: EXE, ARGS ("|"-separated), EXPECT_EXIT, STDOUT_MATCH, STDOUT_NOT_MATCH,
# STDERR_MATCH, STDERR_NOT_MATCH, WORKDIR.
string(REPLACE "|" ";" args "${ARGS}")
file(REMOVE_RECURSE "${WORKDIR}")
file(MAKE_DIRECTORY "${WORKDIR}")
execute_process(COMMAND "${EXE}" ${args}
  WORKING_DIRECTORY "${WORKDIR}"
  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("exit ${code}\n--- stdout\n${out}--- stderr\n${err}---")
if(NOT code STREQUAL "${EXPECT_EXIT}")
  message(FATAL_ERROR "expected exit code ${EXPECT_EXIT}, got ${code}")
endif()
if(DEFINED STDOUT_MATCH AND NOT out MATCHES "${STDOUT_MATCH}")
  message(FATAL_ERROR "stdout does not match: ${STDOUT_MATCH}")
endif()
if(DEFINED STDOUT_NOT_MATCH AND out MATCHES "${STDOUT_NOT_MATCH}")
  message(FATAL_ERROR "stdout must not match: ${STDOUT_NOT_MATCH}")
endif()
if(DEFINED STDERR_MATCH AND NOT err MATCHES "${STDERR_MATCH}")
  message(FATAL_ERROR "stderr does not match: ${STDERR_MATCH}")
endif()
if(DEFINED STDERR_NOT_MATCH AND err MATCHES "${STDERR_NOT_MATCH}")
  message(FATAL_ERROR "stderr must not match: ${STDERR_NOT_MATCH}")
endif()
file(GLOB written "${WORKDIR}/*")
if(written)
  message(FATAL_ERROR "semo-verify wrote files it should not have: ${written}")
endif()
